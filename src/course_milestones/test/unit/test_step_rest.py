"""steps.motion's judging of where a turtle comes to rest (`stops_at`) and of a turn in place
(`turns`), on generated poses at turtlesim's tick: a motion that ends where and as asked holds, a
near miss says what the turtle did; and the loader's checks of the two steps. No master."""
import math

import pytest
from hypothesis import given, settings, strategies as st

from course_format import course_file
from course_milestones.steps import drawing, motion, shapes
from course_milestones.turning import wrap

STILL = 31  # poses of 0.5 s at turtlesim's 62.5 Hz (rest.py: ceil(still / TICK))


def drive(x, y, theta, distance, speed=1.0, tick=0.016):
    """Poses of a turtle driving `distance` m straight ahead at `speed`, one a tick."""
    steps = max(1, int(round(abs(distance) / (speed * tick))))
    return [(x + distance * i / steps * math.cos(theta), y + distance * i / steps * math.sin(theta), theta)
            for i in range(steps + 1)]


def spin(x, y, theta, angle, rate=1.0, tick=0.016, drift=0.0):
    """Poses of a turtle turning `angle` rad in place at `rate` rad/s (moving `drift` m along x as it does)."""
    steps = max(1, int(round(abs(angle) / (rate * tick))))
    return [(x + drift * i / steps, y, wrap(theta + angle * i / steps)) for i in range(steps + 1)]


def rest(poses, count=STILL + 5):
    return list(poses) + [poses[-1]] * count


# -- at rest ---------------------------------------------------------------------------------------------

def test_a_turtle_is_at_rest_only_once_it_moved_and_then_stood_still():
    assert not motion.at_rest([(5.0, 5.0, 0.0)] * 100, STILL)   # never moved: not a motion that ended
    moving = drive(2, 5, 0, 3)
    assert not motion.at_rest(moving, STILL)
    assert not motion.at_rest(moving + [moving[-1]] * (STILL - 1), STILL)   # not long enough
    assert motion.at_rest(moving + [moving[-1]] * STILL, STILL)
    turning = spin(5, 5, 0, 1.0, rate=0.2)   # a slow turn is no rest, however small each tick's change
    assert motion.at_rest(turning + [turning[-1]] * STILL, STILL) and not motion.at_rest(turning, STILL)


def test_what_a_turtle_did_not_do_is_not_moving():
    assert not motion.went([(1.0, 1.0, 0.5)] * 10) and not motion.went([])
    assert motion.went(drive(1, 1, 0, 0.2)) and motion.went(spin(1, 1, 0, 0.2))


# -- stops_at --------------------------------------------------------------------------------------------

@given(st.floats(1, 10), st.floats(1, 10), st.floats(-math.pi, math.pi), st.floats(0.5, 4))
@settings(max_examples=60, deadline=None)
def test_a_drive_that_ends_at_the_point_and_heading_holds(x, y, theta, distance):
    poses = rest(drive(x, y, theta, distance))
    gx, gy = x + distance * math.cos(theta), y + distance * math.sin(theta)
    assert motion.judge_stop(poses, gx, gy, 0.01, theta, 0.01).holds
    assert motion.judge_stop(poses, gx, gy, 0.01).holds and motion.judge_stop(poses, heading=theta).holds


def test_a_drive_that_stops_short_says_where_it_stands_and_how_far_off():
    poses = rest(drive(2, 5.5, 0, 2.6))
    verdict = motion.judge_stop(poses, 5, 5.5, 0.1, 0, 0.05)
    assert not verdict.holds
    assert verdict.text == ("it stands at (4.60, 5.50), heading 0.00 rad: 0.40 m from (5, 5.5), where the text puts "
                            "it (within 0.1 m)")
    turned = motion.judge_stop(rest(drive(2, 5.5, 0.3, 3)), heading=0, heading_tolerance=0.05)
    assert not turned.holds and "its heading 0.30 rad off the text's 0 rad (within 0.05)" in turned.text


def test_a_heading_is_judged_across_the_wrap():
    poses = [(1.0, 1.0, math.pi - 0.01), (1.0, 1.0, -math.pi + 0.01)]
    assert motion.judge_stop(poses, heading=math.pi, heading_tolerance=0.02).holds
    assert motion.judge_stop(poses, heading=-math.pi, heading_tolerance=0.02).holds


# -- turns -----------------------------------------------------------------------------------------------

@given(st.floats(-math.pi, math.pi), st.floats(0.3, 7.0), st.sampled_from((1.0, -1.0)))
@settings(max_examples=60, deadline=None)
def test_a_turn_in_place_by_the_angle_holds_past_pi_too(start, size, way):
    poses = rest(spin(5.5, 5.5, start, way * size))
    assert motion.judge_turn(poses, way * size, 0.02).holds
    assert motion.judge_turn(poses, -way * size, 0.02, either_way=True).holds
    assert not motion.judge_turn(poses, -way * size, 0.02).holds  # the other way


def test_a_turn_short_of_the_angle_the_wrong_way_or_moving_says_so():
    short = motion.judge_turn(rest(spin(5, 5, 0, 1.40)), 1.5708)
    assert not short.holds and short.text == "it turned 1.40 rad left; the text asks a turn of 1.5708 rad left " \
                                             "(within 0.05 rad)"
    wrong_way = motion.judge_turn(rest(spin(5, 5, 0, -1.5708)), 1.5708)
    assert not wrong_way.holds and "it turned 1.57 rad right; the text asks a turn of 1.5708 rad left" in \
        wrong_way.text
    drifting = motion.judge_turn(rest(spin(5, 5, 0, 1.5708, drift=0.5)), 1.5708, drift=0.05)
    assert not drifting.holds and "but it moved 0.50 m from (5.00, 5.00), at (5.50, 5.00): a turn in place stays " \
                                  "within 0.05 m" in drifting.text


def test_no_poses_are_judged_without_raising():
    for verdict in (motion.judge_stop([], 1, 1), motion.judge_turn([], 1.0)):
        assert not verdict.holds and verdict.text == "no pose was received"
    assert not motion.at_rest([], STILL) and not motion.at_rest([(1.0, 1.0, 0.0)], 0)


# -- a turtle outside a box ----------------------------------------------------------------------------------

def test_a_turtle_spawned_outside_the_box_is_said_to_appear_there_not_to_leave_it():
    box = shapes.Box(1.5, 2.5, 2.5, 3.5)
    spawned = drawing.outside_words("turtle2", box, (3.0, 2.0), 0, True, "calling /spawn_two")
    assert spawned == ("turtle2 appeared at (3.00, 2.00) after calling /spawn_two, outside the box x 1.5..2.5, "
                       "y 2.5..3.5")
    assert "left" not in spawned and "0.0 s" not in spawned
    there = drawing.outside_words("turtle1", box, (3.0, 2.0), 0, False, "calling /spawn_two")
    assert there.startswith("turtle1 was already at (3.00, 2.00) when calling /spawn_two began, outside the box")
    left = drawing.outside_words("turtle1", box, (2.5, 3.0), 125, False, "publishing x")
    assert left == "turtle1 left the box x 1.5..2.5, y 2.5..3.5 at (2.50, 3.00), about 2.0 s after publishing x"


# -- the loader ------------------------------------------------------------------------------------------

COURSE = """name: t
title: t
milestones:
  - id: a
    title: a
    text: a
    world: [turtlesim]
    steps:
      - stops_at: {x: 5, y: 5.5, tolerance: 0.1, heading: 0}
      - stops_at: {heading: 1.57, heading_tolerance: 0.1, still: 1}
      - turns: {angle: -3.0, tolerance: 0.05, drift: 0.1}
      - turns: {angle: 1.5708, either_way: true}
%s"""


def test_the_loader_takes_the_rest_steps_and_says_what_is_wrong_with_one(tmp_path):
    path = tmp_path / "course.yaml"
    path.write_text(COURSE % "")
    steps = course_file.load(str(path)).milestones[0].steps
    assert [s.primitive for s in steps] == ["stops_at", "stops_at", "turns", "turns"]
    assert steps[0].params["turtle"] == "turtle1" and steps[0].params["still"] == 0.5
    assert steps[3].params["tolerance"] == 0.05 and steps[3].params["drift"] == 0.05
    wrong = ["stops_at: {x: 5}", "stops_at: {tolerance: 0.2}", "stops_at: {x: 1, y: 1, still: 0}",
             "turns: {angle: 0}", "turns: {tolerance: 0.1}", "turns: {angle: 1, drift: -1}"]
    path.write_text(COURSE % "".join("      - %s\n" % step for step in wrong))
    with pytest.raises(course_file.CourseError) as error:
        course_file.load(str(path))
    said = str(error.value)
    for text in ("steps[4].stops_at.y: missing: a point is x and y",
                 "steps[5].stops_at: give the point it stops at (x, y), its heading, or both",
                 "steps[6].stops_at.still", "steps[7].turns.angle: 0: a turn is by an angle other than 0 rad",
                 "steps[8].turns.angle: missing", "steps[9].turns.drift"):
        assert text in said, said
