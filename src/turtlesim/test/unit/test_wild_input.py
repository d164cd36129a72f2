"""Regressions from fuzzing (issue 9): no input, however huge, stops the tick or makes the pose
non-finite, unpublishable or unwrapped."""
import math
import random
import struct
import threading

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from course_testkit.fuzz import FLOAT32_MAX as FUZZ_FLOAT32_MAX
from course_testkit.fuzz import finite_floats, is_wrapped_angle, wild_floats
from turtlesim.canvas import Canvas
from turtlesim.constants import CENTRE, FLOAT32_MAX, MAX_REACH, TICK, WORLD_SIZE
from turtlesim.frame import TurtleError, TurtleFrame
from turtlesim.node import background_from
from turtlesim.pen import Pen
from turtlesim.ticker import Ticker
from turtlesim import turtle as turtle_module
from turtlesim.turtle import Turtle, wrap_angle

POSE = struct.Struct("<5f")  # turtlesim/Pose on the wire


def assert_publishable(t: Turtle) -> None:
    fields = (t.x, t.y, t.theta, t.linear_velocity, t.w)
    assert all(math.isfinite(v) for v in fields), fields
    POSE.pack(*fields)  # OverflowError here killed the tick thread
    assert 0.0 <= t.x <= WORLD_SIZE and 0.0 <= t.y <= WORLD_SIZE
    assert -math.pi <= t.theta < math.pi


def test_float32_max_is_the_fuzzers():
    assert FLOAT32_MAX == FUZZ_FLOAT32_MAX
    struct.pack("<f", FLOAT32_MAX)


@pytest.mark.parametrize("theta", [1.6e16, 1e18 * TICK, 1e18, -1e18, FLOAT32_MAX, 1e300, -1.7e308,
                                   math.pi, -math.pi, 3 * math.pi, math.nextafter(math.pi, 0.0)])
def test_wrap_angle_stays_in_half_open_range_for_huge_values(theta):
    wrapped = wrap_angle(theta)
    assert -math.pi <= wrapped < math.pi, wrapped  # was -4.0 for 1.6e16


@settings(database=None)
@given(finite_floats())
def test_wrap_angle_is_in_range_and_keeps_the_direction(theta):
    wrapped = wrap_angle(theta)
    assert -math.pi <= wrapped < math.pi and is_wrapped_angle(wrapped)
    if abs(theta) < 1e6:
        assert math.cos(wrapped) == pytest.approx(math.cos(theta), abs=1e-9)
        assert math.sin(wrapped) == pytest.approx(math.sin(theta), abs=1e-9)


@pytest.mark.parametrize("vx, vy, w", [(1e308, 0.0, 0.0), (-1e308, 1e308, 1e308), (3.5e38, 0.0, -3.5e38)])
def test_huge_command_is_clamped_to_float32_and_says_so(vx, vy, w):
    t = Turtle(CENTRE, CENTRE, 0.0)
    note = t.command(vx, vy, w, now=0.0)
    assert "beyond float32's range, clamped" in note
    for _ in range(3):
        t.step(TICK, now=0.0)
        assert_publishable(t)


def test_ordinary_command_is_kept_exactly():
    t = Turtle(CENTRE, CENTRE, 0.0)
    assert t.command(2.0, -1.0, FLOAT32_MAX, now=0.0) is None
    assert (t.vx, t.vy, t.w) == (2.0, -1.0, FLOAT32_MAX)


def test_huge_turn_rate_keeps_theta_wrapped():
    t = Turtle(CENTRE, CENTRE, 0.0)
    t.command(0.0, 0.0, 1e18, now=0.0)
    for _ in range(50):
        t.step(TICK, now=0.0)
        assert -math.pi <= t.theta < math.pi  # was -4.0


def test_huge_relative_teleports_stay_finite():
    t = Turtle(CENTRE, CENTRE, 0.0)
    for _ in range(3):
        t.teleport_relative(1.7e308, 1.7e308)  # theta and x overflowed to inf, then cos(inf) raised
    result = t.step(TICK, now=0.0)
    assert_publishable(t)
    assert all(math.isfinite(v) for segment in result.segments for point in segment for v in point)


def test_far_absolute_teleport_ends_where_upstream_does_and_draws_the_same_line():
    t = Turtle(5.0, 5.0, 0.0)
    t.teleport_absolute(1e300, 4.0, 1e300)
    result = t.step(TICK, now=0.0)
    assert (t.x, t.y) == (WORLD_SIZE, 4.0)  # the wall clamp, as upstream: y kept
    assert result.clamped_from is not None
    start, end = result.segments[0]
    assert start == (5.0, 5.0) and end[0] == WORLD_SIZE + MAX_REACH
    assert (end[1] - 5.0) / (end[0] - 5.0) == pytest.approx(-1.0 / 1e300, abs=1e-12)
    assert_publishable(t)


def test_drawn_end_keeps_the_direction():
    assert turtle_module.drawn_end((1.0, 1.0), (3.0, 2.0)) == (3.0, 2.0)
    x, y = turtle_module.drawn_end((1.0, 1.0), (-1e300, -2e300))
    assert y == -MAX_REACH and (y - 1.0) / (x - 1.0) == pytest.approx(2.0)


def test_huge_spawn_is_placed_within_reach_and_wrapped():
    t = Turtle(1e300, -1e300, 1e300)
    assert (t.x, t.y) == (WORLD_SIZE + MAX_REACH, -MAX_REACH)
    assert -math.pi <= t.theta < math.pi
    t.step(TICK, now=0.0)
    assert_publishable(t)


OPERATIONS = st.one_of(
    st.tuples(st.just("command"), wild_floats(), wild_floats(), wild_floats()),
    st.tuples(st.just("teleport_absolute"), wild_floats(), wild_floats(), wild_floats()),
    st.tuples(st.just("teleport_relative"), wild_floats(), wild_floats()),
    st.tuples(st.just("step"),))


@settings(max_examples=300, deadline=None, database=None)
@given(st.lists(OPERATIONS, max_size=12))
def test_any_sequence_of_requests_leaves_a_publishable_pose(operations):
    t = Turtle(CENTRE, CENTRE, 0.0)
    for name, *args in operations:
        if name == "step":
            t.step(TICK, now=0.0)
            assert_publishable(t)
            continue
        if name == "command":
            args.append(0.0)
        try:
            getattr(t, name)(*args)
        except ValueError as err:
            assert "non-finite" in str(err)
            assert not all(math.isfinite(a) for a in args)
    t.step(TICK, now=0.0)
    assert_publishable(t)


class Exploding(Turtle):
    def step(self, dt, now):
        self.x = math.nan
        raise RuntimeError("boom")


def test_a_failing_turtle_is_stopped_and_the_others_move_on():
    frame = TurtleFrame(Canvas(), rng=random.Random(1))
    frame.spawn("", CENTRE, CENTRE, 0.0)
    frame.turtles["bad"] = Exploding(2.0, 2.0, 0.0)
    frame.turtles["bad"].command(1.0, 0.0, 0.0, now=0.0)
    frame.turtles["turtle1"].command(1.0, 0.0, 0.0, now=0.0)
    updates = {u.name: u for u in frame.update(TICK, 0.0)}
    assert updates["turtle1"].error is None and frame.turtles["turtle1"].x > CENTRE
    assert isinstance(updates["bad"].error, RuntimeError)
    bad = frame.turtles["bad"]
    assert (bad.x, bad.y, bad.vx) == (2.0, 2.0, 0.0)


def test_ticker_survives_a_failing_tick():
    errors, ticks, done = [], [], threading.Event()

    def tick():
        ticks.append(1)
        if len(ticks) == 1:
            raise OverflowError("float too large to pack with f format")
        if len(ticks) >= 3:
            done.set()

    ticker = Ticker(0.005, tick, on_error=errors.append)
    ticker.start()
    try:
        assert done.wait(5.0), "the ticker died with its first tick"
    finally:
        ticker.stop()
    assert ticker.failed_ticks == 1 and isinstance(errors[0], OverflowError)


def test_a_second_spelling_of_a_turtles_namespace_is_refused():
    frame = TurtleFrame(Canvas(), canonical=lambda n: n if n.startswith("/") else "/" + n)
    frame.spawn("", CENTRE, CENTRE, 0.0)
    with pytest.raises(TurtleError, match=r"A turtled named \[/turtle1\] already exists \(as \[turtle1\]\)"):
        frame.spawn("/turtle1", 1.0, 1.0, 0.0)
    frame.spawn("/turtle2", 1.0, 1.0, 0.0)
    assert frame.spawn("", 1.0, 1.0, 0.0) == "turtle3"


@pytest.mark.parametrize("bad", ["turtle2\n", "a\n", "\n"])
def test_trailing_newline_is_not_a_name(bad):
    frame = TurtleFrame(Canvas())
    with pytest.raises(TurtleError, match="invalid turtle name"):
        frame.spawn(bad, 1.0, 1.0, 0.0)


@pytest.mark.parametrize("value", [math.inf, -math.inf, math.nan, "x", None, [1]])
def test_background_param_that_is_no_colour_falls_back(value):
    assert background_from({"background_r": value})[0] == 69


def test_pen_numbers_are_held_in_uint8_range():
    assert Pen().set(300, -5, 255, 999, 0) == Pen(255, 0, 255, 255, True)
