"""The world: spawn naming and errors, kill, reset, colour sensor read from the drawn canvas."""
import math
import random

import pytest

from turtlesim.canvas import Canvas, rgb888_bytes
from turtlesim.constants import CANVAS_PX, CENTRE, DEFAULT_BACKGROUND_RGB, TICK
from turtlesim.frame import TurtleError, TurtleFrame
from turtlesim.names import name_error


@pytest.fixture
def frame():
    f = TurtleFrame(Canvas(), rng=random.Random(1))
    f.spawn("", CENTRE, CENTRE, 0.0)
    return f


def test_first_turtle_is_turtle1(frame):
    assert list(frame.turtles) == ["turtle1"]


def test_empty_name_counts_up_and_skips_taken_names(frame):
    frame.spawn("turtle3", 1, 1, 0)
    assert frame.spawn("", 1, 1, 0) == "turtle2"
    assert frame.spawn("", 1, 1, 0) == "turtle4"


def test_duplicate_name_fails(frame):
    with pytest.raises(TurtleError, match=r"A turtled named \[turtle1\] already exists"):
        frame.spawn("turtle1", 1, 1, 0)


@pytest.mark.parametrize("bad", ["9lives", "a b", "~private", "a//b", "x-y", "/"])
def test_invalid_names_fail(frame, bad):
    with pytest.raises(TurtleError, match="invalid turtle name"):
        frame.spawn(bad, 1, 1, 0)
    assert name_error(bad)


@pytest.mark.parametrize("good", ["leo", "ns/leo", "/abs", "t_2"])
def test_valid_names(good):
    assert name_error(good) is None


def test_non_finite_spawn_fails_without_adding_a_turtle(frame):
    with pytest.raises(TurtleError, match="non-finite"):
        frame.spawn("nan_turtle", float("nan"), 1, 0)
    assert not frame.has("nan_turtle")


def test_kill(frame):
    frame.kill("turtle1")
    assert not frame.turtles
    with pytest.raises(TurtleError, match=r"Tried to kill turtle \[turtle1\], which does not exist"):
        frame.kill("turtle1")


def test_reset_leaves_only_turtle1_at_centre_and_restarts_numbering(frame):
    frame.spawn("", 1, 1, 0)
    frame.turtles["turtle1"].teleport_absolute(1, 1, 1)
    frame.update(TICK, 0.0)
    removed, first = frame.reset((0, 0, 0))
    assert removed == ["turtle1", "turtle2"] and first == "turtle1"
    t = frame.turtles["turtle1"]
    assert (t.x, t.y, t.theta) == (CENTRE, CENTRE, 0.0)
    assert frame.spawn("", 1, 1, 0) == "turtle2"
    assert frame.canvas.colour_at(1, 1) == (0, 0, 0)


def test_colour_sensor_reads_the_pen_just_drawn_and_background_elsewhere(frame):
    t = frame.turtles["turtle1"]
    t.set_pen(255, 0, 0, 3, 0)
    t.command(2.0, 0.0, 0.0, now=0.0)
    updates = frame.update(TICK, 0.0)
    assert updates[0].colour == (255, 0, 0)
    assert frame.canvas.colour_at(1.0, 1.0) == DEFAULT_BACKGROUND_RGB


def test_pen_off_draws_nothing(frame):
    t = frame.turtles["turtle1"]
    t.set_pen(0, 0, 0, 0, 1)
    t.command(2.0, 0.0, 0.0, now=0.0)
    assert frame.update(TICK, 0.0)[0].colour == DEFAULT_BACKGROUND_RGB


def test_turtles_are_not_in_the_path_image(frame):
    frame.update(TICK, 0.0)
    assert frame.canvas.colour_at(CENTRE, CENTRE) == DEFAULT_BACKGROUND_RGB


def test_clear_fills_background(frame):
    frame.turtles["turtle1"].command(1.0, 0.0, 0.0, now=0.0)
    frame.update(TICK, 0.0)
    frame.clear((10, 20, 30))
    assert frame.canvas.colour_at(CENTRE, CENTRE) == (10, 20, 30)


def test_render_draws_turtles_over_the_paths(frame):
    image = frame.render()
    assert (image.width(), image.height()) == (CANVAS_PX, CANVAS_PX)
    data = rgb888_bytes(image)
    assert len(data) == CANVAS_PX * CANVAS_PX * 3
    centre = (250 * CANVAS_PX + 250) * 3
    assert tuple(data[centre:centre + 3]) != DEFAULT_BACKGROUND_RGB
    assert tuple(data[0:3]) == DEFAULT_BACKGROUND_RGB


def test_thick_pen_colours_a_band(frame):
    t = frame.turtles["turtle1"]
    t.set_pen(0, 255, 0, 9, 0)
    t.teleport_absolute(2.0, 2.0, 0.0)
    t.teleport_absolute(4.0, 2.0, 0.0)
    frame.update(TICK, 0.0)
    assert frame.canvas.colour_at(3.0, 2.0 + 3.0 / 45.0) == (0, 255, 0)
    assert frame.canvas.colour_at(3.0, 2.0 + 8.0 / 45.0) == DEFAULT_BACKGROUND_RGB
    assert math.isfinite(t.x)
