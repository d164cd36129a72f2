"""Turtle physics: kinematics, wrap, clamp, timeout, teleports, bad input."""
import math

import pytest

from turtlesim.constants import CENTRE, COMMAND_TIMEOUT, TICK, WORLD_SIZE
from turtlesim.turtle import Turtle, wrap_angle


def test_world_size_matches_upstream():
    assert WORLD_SIZE == pytest.approx(11.088889, abs=1e-6)
    assert CENTRE == pytest.approx(5.544445, abs=1e-6)


@pytest.mark.parametrize("theta, wrapped", [
    (0.0, 0.0), (math.pi, -math.pi), (-math.pi, -math.pi), (3 * math.pi / 2, -math.pi / 2),
    (-3 * math.pi / 2, math.pi / 2), (7.0, 7.0 - 2 * math.pi), (100.0, 100.0 - 16 * 2 * math.pi)])
def test_wrap_angle_into_half_open_interval(theta, wrapped):
    assert wrap_angle(theta) == pytest.approx(wrapped)
    assert -math.pi <= wrap_angle(theta) < math.pi


def test_forward_motion_integrates_dt_per_tick():
    t = Turtle(1.0, 1.0, 0.0)
    t.command(2.0, 0.0, 0.0, now=0.0)
    for _ in range(10):
        t.step(TICK, now=0.1)
    assert t.x == pytest.approx(1.0 + 2.0 * TICK * 10)
    assert t.y == pytest.approx(1.0)


def test_turn_happens_before_move():
    t = Turtle(5.0, 5.0, 0.0)
    t.command(1.0, 0.0, 1.0, now=0.0)
    t.step(TICK, now=0.0)
    assert t.theta == pytest.approx(TICK)
    assert t.x == pytest.approx(5.0 + math.cos(TICK) * TICK)
    assert t.y == pytest.approx(5.0 + math.sin(TICK) * TICK)


def test_holonomic_linear_y_moves_sideways():
    t = Turtle(5.0, 5.0, 0.0)
    t.command(0.0, 1.0, 0.0, now=0.0)
    t.step(TICK, now=0.0)
    assert t.x == pytest.approx(5.0)
    assert t.y == pytest.approx(5.0 + TICK)
    assert t.linear_velocity == pytest.approx(1.0)


def test_theta_stays_wrapped_while_spinning():
    t = Turtle(5.0, 5.0, 3.1)
    t.command(0.0, 0.0, 2.0, now=0.0)
    for _ in range(50):
        t.step(TICK, now=0.0)
        assert -math.pi <= t.theta < math.pi


def test_old_command_stops_the_turtle():
    t = Turtle(5.0, 5.0, 0.0)
    t.command(1.0, 0.0, 1.0, now=10.0)
    t.step(TICK, now=10.0 + COMMAND_TIMEOUT - 0.01)
    assert t.vx == 1.0
    x = t.x
    t.step(TICK, now=10.0 + COMMAND_TIMEOUT + 0.01)
    assert (t.vx, t.vy, t.w) == (0.0, 0.0, 0.0)
    assert t.x == x


def test_wall_clamp_reports_canvas_coordinates_before_clamping():
    t = Turtle(0.01, 3.0, math.pi)
    t.command(2.0, 0.0, 0.0, now=0.0)
    result = t.step(TICK, now=0.0)
    assert t.x == 0.0
    assert result.clamped_from[0] == pytest.approx(0.01 - 2.0 * TICK)
    assert result.clamped_from[1] == pytest.approx(WORLD_SIZE - 3.0)


def test_clamp_on_top_wall():
    t = Turtle(3.0, WORLD_SIZE - 0.001, math.pi / 2)
    t.command(1.0, 0.0, 0.0, now=0.0)
    assert t.step(TICK, now=0.0).clamped_from is not None
    assert t.y == WORLD_SIZE


def test_teleports_are_queued_until_the_next_tick():
    t = Turtle(5.0, 5.0, 0.0)
    t.teleport_absolute(1.0, 2.0, 0.5)
    assert (t.x, t.y) == (5.0, 5.0)
    result = t.step(TICK, now=0.0)
    assert (t.x, t.y, t.theta) == (1.0, 2.0, 0.5)
    assert result.segments[0] == ((5.0, 5.0), (1.0, 2.0))


def test_teleport_absolute_caps_y_at_the_top_like_upstream():
    t = Turtle(5.0, 5.0, 0.0)
    t.teleport_absolute(3.0, 50.0, 0.0)
    assert t.step(TICK, now=0.0).clamped_from is None
    assert t.y == WORLD_SIZE


def test_teleport_relative_turns_then_moves():
    t = Turtle(5.0, 5.0, 0.0)
    t.teleport_relative(2.0, math.pi / 2)
    t.step(TICK, now=0.0)
    assert t.x == pytest.approx(5.0)
    assert t.y == pytest.approx(7.0)
    assert t.theta == pytest.approx(math.pi / 2)


def test_teleports_apply_in_order():
    t = Turtle(5.0, 5.0, 0.0)
    t.teleport_absolute(1.0, 1.0, 0.0)
    t.teleport_relative(1.0, 0.0)
    result = t.step(TICK, now=0.0)
    assert t.x == pytest.approx(2.0) and len(result.segments) == 2


@pytest.mark.parametrize("call", [
    lambda t: t.command(float("nan"), 0.0, 0.0, now=0.0),
    lambda t: t.command(0.0, 0.0, float("inf"), now=0.0),
    lambda t: t.teleport_absolute(float("inf"), 1.0, 0.0),
    lambda t: t.teleport_relative(1.0, float("nan")),
])
def test_non_finite_input_is_refused_and_pose_stays_finite(call):
    t = Turtle(5.0, 5.0, 0.0)
    t.command(1.0, 0.0, 0.0, now=0.0)
    with pytest.raises(ValueError, match="non-finite"):
        call(t)
    t.step(TICK, now=0.0)
    assert all(math.isfinite(v) for v in (t.x, t.y, t.theta, t.vx, t.vy, t.w))


def test_spawn_with_non_finite_pose_is_refused():
    with pytest.raises(ValueError):
        Turtle(float("nan"), 1.0, 0.0)
