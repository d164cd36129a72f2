"""The color milestone's spots stay deep in the corners and its red test accepts reds, not the defaults."""
import math

import pen_spots as ps
from turtlesim.constants import DEFAULT_BACKGROUND_RGB, DEFAULT_PEN_RGB, WORLD_SIZE


def test_circles_stay_deep_in_the_corners():
    for spot in ps.corners():
        x, y, theta = spot.start()
        linear, angular = ps.circle_command()
        assert math.isclose(linear / angular, ps.CIRCLE_RADIUS)
        for v in (spot.x, spot.y):
            nearest_wall = min(v, WORLD_SIZE - v)
            assert nearest_wall - ps.CIRCLE_RADIUS >= 0.25 and nearest_wall + ps.CIRCLE_RADIUS <= 0.75
        assert math.isclose(math.hypot(x - spot.x, y - spot.y), ps.CIRCLE_RADIUS) and theta == 0.0


def test_tour_alternates_corner_and_middle():
    spots = ps.tour()
    assert [s.corner for s in spots] == [True, False] * 4
    assert len({s.name for s in spots if s.corner}) == 4


def test_red_and_not_red():
    assert ps.is_red((255, 0, 0)) and ps.is_red((200, 30, 60))
    assert not ps.is_red(DEFAULT_PEN_RGB) and not ps.is_red(DEFAULT_BACKGROUND_RGB)
    assert not ps.is_red((255, 255, 0)) and not ps.is_red((100, 0, 0))


def test_settled_needs_the_last_samples_to_agree():
    red, pen = (255, 0, 0), DEFAULT_PEN_RGB
    assert ps.settled([pen] * 3 + [red] * 5, True)
    assert not ps.settled([red] * 4 + [pen], True)
    assert ps.settled([red] * 2 + [pen] * 5, False)
    assert not ps.settled([red] * 3, True)
