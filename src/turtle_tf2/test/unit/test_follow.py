import math

import pytest

from turtle_tf2.follow import FollowGains, VelocityCommand, steer


def test_leader_straight_ahead_drives_without_turning():
    assert steer(2.0, 0.0) == VelocityCommand(1.0, 0.0)


def test_leader_to_the_left_turns_left():
    command = steer(0.0, 3.0)
    assert command.linear == pytest.approx(1.5)
    assert command.angular == pytest.approx(math.pi / 2)


def test_leader_behind_turns_around():
    assert abs(steer(-1.0, 1e-9).angular) == pytest.approx(math.pi)


def test_gains_scale_the_law():
    command = steer(3.0, 4.0, FollowGains(rotation=4.0, forward=0.2))
    assert command.linear == pytest.approx(1.0)
    assert command.angular == pytest.approx(4.0 * math.atan2(4.0, 3.0))


def test_stops_at_the_leader():
    assert steer(0.01, -0.01) == VelocityCommand(0.0, 0.0)


def test_closed_loop_reaches_a_still_leader():
    # Unicycle follower at (4, 2, 0), leader still at the turtlesim centre: the law must converge.
    x, y, theta, dt = 4.0, 2.0, 0.0, 0.016
    leader = (5.544445, 5.544445)
    for _ in range(int(20.0 / dt)):
        dx_w, dy_w = leader[0] - x, leader[1] - y
        dx = math.cos(theta) * dx_w + math.sin(theta) * dy_w
        dy = -math.sin(theta) * dx_w + math.cos(theta) * dy_w
        command = steer(dx, dy)
        theta += command.angular * dt
        x += math.cos(theta) * command.linear * dt
        y += math.sin(theta) * command.linear * dt
    assert math.hypot(leader[0] - x, leader[1] - y) < 0.1


@pytest.mark.parametrize("bad", [(math.nan, 0.0), (0.0, math.inf)])
def test_non_finite_offset_is_refused(bad):
    with pytest.raises(ValueError, match="not finite"):
        steer(*bad)


@pytest.mark.parametrize("field", ["rotation", "forward", "stop_distance"])
def test_bad_gains_are_refused(field):
    with pytest.raises(ValueError, match=field):
        FollowGains(**{field: -1.0})
