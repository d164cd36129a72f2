"""The pure logic of the steps (course_milestones.steps.predicates, .motion): predicates on values,
field paths into messages, rates from arrival times, one-line descriptions, turtle motion. No master."""
import math

import pytest
from geometry_msgs.msg import Pose2D, Twist
from hypothesis import given, settings, strategies as st
from std_msgs.msg import String

from course_format import schema
from course_milestones.steps import motion, predicates
from course_milestones.steps.predicates import FieldMissing, describe, field, holds, problem, rate, rate_problem

# Any value a message field, a parameter or a service answer may hold, nested.
VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=20) | st.binary(max_size=10),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=5), inner, max_size=4),
    max_leaves=12)
PREDICATE_VALUES = st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8) \
    | st.lists(st.floats() | st.integers(), max_size=3)
PREDICATES = st.dictionaries(st.sampled_from(schema.PREDICATE_KEYS + ("other",)), PREDICATE_VALUES, max_size=3) \
    | PREDICATE_VALUES


# -- predicates ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("predicate, value", [
    ({"equals": "hello"}, "hello"),
    ({"equals": 42}, 42),
    ({"differs": "turtle2"}, "turtle3"),
    ({"differs": 0, "nonempty": True}, "x"),
    ({"approx": 1.0}, 1.0005),
    ({"approx": 1.0, "tolerance": 0.5}, 1.4),
    ({"matches": "^hello world [0-9.]+$"}, "hello world 12.5"),
    ({"matches": "42"}, 42),
    ({"between": [0, 11.1]}, 5.5),
    ({"nonempty": True}, "x"),
    ({"nonempty": False}, []),
    ({"nonempty": True, "matches": "a"}, "cat"),
])
def test_a_predicate_holds(predicate, value):
    verdict = holds(predicate, value)
    assert verdict.holds, verdict.text


@pytest.mark.parametrize("predicate, value, words", [
    ({"equals": "hello"}, "bye", "expected 'hello'"),
    ({"differs": "turtle2"}, "turtle2", "expected a value other than 'turtle2'"),
    ({"approx": 1.0}, 1.1, "expected 1 (within 0.001)"),
    ({"approx": 1.0}, "1.0", "not a number"),
    ({"matches": "^hello"}, "say hello", "match '^hello'"),
    ({"between": [0, 1]}, 2, "between 0 and 1"),
    ({"between": [0, 1]}, True, "not a number"),
    ({"nonempty": True}, "", "nonempty"),
    ({"nonempty": True}, None, "nonempty"),
    ({"nonempty": True, "matches": "a"}, "dog", "match 'a'"),
])
def test_a_predicate_fails_saying_what_it_expected(predicate, value, words):
    verdict = holds(predicate, value)
    assert not verdict.holds
    assert words in verdict.text and describe(value) in verdict.text


@pytest.mark.parametrize("predicate, words", [
    ({}, "a predicate is a mapping"),
    ("hello", "a predicate is a mapping"),
    ({"equal": 1}, "unknown predicate key equal"),
    ({"tolerance": 1}, "tolerance goes with approx"),
    ({"approx": "one"}, "approx takes a number"),
    ({"approx": 1, "tolerance": -1}, "tolerance takes a number >= 0"),
    ({"matches": "(unclosed"}, "not a regular expression"),
    ({"between": [2, 1]}, "LO <= HI"),
    ({"between": [1]}, "between takes [LO, HI]"),
    ({"nonempty": "yes"}, "nonempty takes true or false"),
])
def test_a_course_files_bad_predicate_is_named(predicate, words):
    assert words in problem(predicate)
    verdict = holds(predicate, "anything")
    assert not verdict.holds and words in verdict.text


@settings(max_examples=300, deadline=None)
@given(PREDICATES, VALUES)
def test_a_predicate_never_raises_and_always_says_why(predicate, value):
    verdict = holds(predicate, value)
    assert isinstance(verdict.holds, bool)
    assert isinstance(verdict.text, str) and verdict.text


@settings(max_examples=200, deadline=None)
@given(st.integers() | st.floats(), st.integers() | st.floats(allow_nan=False), st.floats(0, 1e6))
def test_approx_agrees_with_the_distance(value, wanted, tolerance):
    predicate = {"approx": wanted, "tolerance": tolerance}
    try:
        expected = abs(float(value) - float(wanted)) <= tolerance
    except OverflowError:
        expected = False
    assert holds(predicate, value).holds == expected


# -- field paths --------------------------------------------------------------------------------------

def test_a_field_path_reaches_into_messages_mappings_and_lists():
    twist = Twist()
    twist.linear.x = 2.0
    assert field(twist, "linear.x") == 2.0
    assert field({"poses": [{"x": 1}, {"x": 3}]}, "poses[1].x") == 3
    assert field({"poses": [{"x": 1}, {"x": 3}]}, "poses.0.x") == 1
    assert field(String("hi"), "data") == "hi"


@pytest.mark.parametrize("value, path, words", [
    (Twist(), "linear.w", "linear has no field w (it has x, y, z)"),
    (Twist(), "speed", "the message has no field speed (it has linear, angular)"),
    ({"a": [1]}, "a[3]", "a has 1 items, no item 3"),
    ({"a": 1}, "a.b", "a has no field b (it is 1)"),
    (String(), "", "names no field"),
])
def test_a_missing_field_says_what_there_is(value, path, words):
    with pytest.raises(FieldMissing) as caught:
        field(value, path)
    assert words in str(caught.value)


@settings(max_examples=200, deadline=None)
@given(VALUES, st.text(max_size=12))
def test_a_field_path_gives_a_value_or_field_missing(value, path):
    try:
        field(value, path)
    except FieldMissing as err:
        assert str(err)


# -- rates --------------------------------------------------------------------------------------------

def test_rate_counts_intervals_over_their_span():
    assert rate([0.0, 0.1, 0.2, 0.3, 0.4]) == pytest.approx(10.0)
    assert rate([5.0]) is None
    assert rate([1.0, 1.0]) is None


def test_rate_problem_allows_a_little_jitter_and_says_the_bounds():
    assert rate_problem(9.8, 10, None) is None
    assert rate_problem(10.3, None, 10) is None
    assert "at 2 Hz; the text asks for at least 5 Hz" in rate_problem(2.0, 5, None)
    assert "at least 1 Hz and at most 5 Hz" in rate_problem(20.0, 1, 5)
    assert "cannot be measured" in rate_problem(None, 1, None)
    assert rate_problem(None, None, None) is None


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(0, 1e6), max_size=30).map(sorted))
def test_a_rate_is_none_or_positive(arrivals):
    measured = rate(arrivals)
    assert measured is None or (measured > 0 and math.isfinite(measured))


# -- descriptions -------------------------------------------------------------------------------------

def test_a_message_is_described_on_one_line():
    twist = Twist()
    twist.linear.x = 2.0
    assert describe(twist) == "{linear: {x: 2, y: 0, z: 0}, angular: {x: 0, y: 0, z: 0}}"
    assert describe(String("hello")) == "{data: 'hello'}"
    assert describe(list(range(20))) == "[0, 1, 2, 3, 4, 5, 6, 7, ... (12 more)]"
    assert len(describe("x" * 1000, 50)) == 50


@settings(max_examples=200, deadline=None)
@given(VALUES, st.integers(3, 400))
def test_a_description_is_one_bounded_line(value, limit):
    text = describe(value, limit)
    assert isinstance(text, str) and len(text) <= limit


# -- turtle motion ------------------------------------------------------------------------------------

def test_motion_forward_backward_and_turns():
    east = [(5.0, 5.0, 0.0), (6.0, 5.0, 0.0)]
    assert motion.judge(east, "forward", 0.5).holds
    assert not motion.judge(east, "backward", 0.5).holds
    north_facing = [(5.0, 5.0, math.pi / 2), (5.0, 4.0, math.pi / 2)]
    assert motion.judge(north_facing, "backward", 0.5).holds
    turning = [(5.0, 5.0, 3.0), (5.0, 5.0, -3.0)]  # left through the wrap: +0.28 rad
    assert motion.judge(turning, "left", 0.2).holds
    assert not motion.judge(turning, "right", 0.2).holds
    still = [(5.0, 5.0, 0.0), (5.0, 5.0, 0.0)]
    verdict = motion.judge(still, "any", 0.2)
    assert not verdict.holds and "moved 0.00 m" in verdict.text and "move 0.2 m" in verdict.text


def test_motion_without_poses_or_with_an_unknown_direction_fails():
    assert not motion.judge([], "any", 0.1).holds
    assert "not one of" in motion.judge([(0.0, 0.0, 0.0)], "up", 0.1).text


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(*[st.floats(-20, 20)] * 3), min_size=1, max_size=10),
       st.sampled_from(motion.DIRECTIONS), st.floats(0, 5))
def test_motion_judges_any_poses(poses, direction, minimum):
    verdict = motion.judge(poses, direction, minimum)
    assert isinstance(verdict.holds, bool) and verdict.text
    if verdict.holds and direction == "forward":
        assert motion.movement(poses).along >= minimum


def test_every_primitive_of_the_schema_has_a_runner():
    run = pytest.importorskip("course_milestones.steps.run")
    assert set(run.RUNNERS) == set(schema.PRIMITIVES)
    assert run.with_defaults("publishes", {"topic": "/x"})["within"] == 15.0


def test_pose2d_reads_like_a_pose():  # the path syntax works on any generated message
    assert field(Pose2D(1.0, 2.0, 0.5), "theta") == 0.5
    assert not predicates.holds({"between": [0, 0.4]}, 0.5).holds


def test_a_type_steps_keys_are_characters_and_named_keys():
    terminal = pytest.importorskip("course_milestones.steps.terminal")
    assert terminal.keys_of("w<up>x<enter>") == ["w", "up", "x", "\n"]
    assert terminal.keys_of("<upx") == ["<", "u", "p", "x"]
