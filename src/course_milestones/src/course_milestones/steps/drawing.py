"""The drawing steps, on the course's own turtlesim: `draws` (a circle, arc or square drawn since
the last action), `in_bounds` (every pose inside a box for a while) and `pen_colour` (the colour
the pen lays down, read from /TURTLE/color_sensor: the pixel under the turtle, which its pen has
just drawn while it moves with the pen down). The judging is steps.shapes; here are the waiting,
the recording and the failure's sentence."""
from __future__ import annotations

import time
from typing import Callable, Dict, List

from turtlesim.constants import TICK
from turtlesim.msg import Color

from course_milestones.steps import shapes, turtles
from course_milestones.steps.state import StepState, course_error, failed
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

POLL_S = 0.1  # a judgement reads every pose so far: not more often than this


def poses_since_action(state: StepState, turtle: str) -> Callable[[], List[shapes.Pose]]:
    """The turtle's poses from the one before the last action on (from its first pose now on when
    it was not watched then), as a function read again while the step waits."""
    recorder = turtles.watch(state, turtle)
    if turtle not in state.pose_marks:
        state.pose_marks[turtle] = 1 if wait_for(lambda: recorder.count, turtles.POSE_WAIT_S) else 0
    mark = max(state.pose_marks[turtle] - 1, 0)
    return lambda: [(m.x, m.y, m.theta) for m in recorder.messages[mark:]]


def no_pose(turtle: str) -> Exception:
    return failed("not_moving", "no pose of %s (/%s/pose): is turtlesim running, with a turtle of that name?"
                  % (turtle, turtle))


def draws(state: StepState, p: Dict, where: str) -> None:
    turtle, shape = p.get("turtle") or "turtle1", p.get("shape")
    if shape not in shapes.SHAPES or (shape == "arc" and not p.get("angle")):
        raise course_error(where, "shape %r: one of %s (an arc with its angle)" % (shape, ", ".join(shapes.SHAPES)))
    since = poses_since_action(state, turtle)
    if not since():
        raise no_pose(turtle)
    numbers = {k: (float(p[k]) if p.get(k) is not None else None) for k in ("radius", "angle", "side")}
    tolerance = float(p.get("tolerance") or 0.0)

    def judged() -> shapes.Drawing:
        return shapes.draws(since(), shape, tolerance=tolerance, **numbers)
    wait_for(lambda: judged().complete, float(p.get("within") or 0.0), POLL_S)
    verdict = judged()
    if verdict.holds:
        return
    cause = "wrong_value" if verdict.moved else "not_moving"
    raise failed(cause, "%s %s: %s%s" % (turtle, state.after_action(), verdict.text,
                                         "" if verdict.moved else "; it did not move"))


def in_bounds(state: StepState, p: Dict, where: str) -> None:
    turtle = p.get("turtle") or "turtle1"
    box = shapes.Box(*(float(p[k]) for k in ("xmin", "xmax", "ymin", "ymax")))
    if box.xmin >= box.xmax or box.ymin >= box.ymax:
        raise course_error(where, "an empty box: x %g..%g, y %g..%g" % box)
    appeared = turtle not in state.pose_marks  # no turtle of that name at the last action: spawned since
    since = poses_since_action(state, turtle)
    if not since():
        raise no_pose(turtle)
    left = state.action_time + float(p.get("for") or 0.0) - time.monotonic()
    wait_for(lambda: shapes.first_outside(since(), box) is not None, max(left, 0.0), POLL_S)
    poses = since()
    index = shapes.first_outside(poses, box)
    if index is None:
        return
    x, y, _ = poses[index]
    raise failed("wrong_value", outside_words(turtle, box, (x, y), index, appeared, state.last_action))


def outside_words(turtle: str, box: shapes.Box, place: shapes.Point, index: int, appeared: bool,
                  action: str) -> str:
    """The first pose outside the box in words: where the turtle was (it appeared there after the
    action, or stood there as it began) when that is its first pose judged, else when it left."""
    where = "the box x %g..%g, y %g..%g" % tuple(box)
    action = action or "the last action"
    if index == 0 and appeared:
        return "%s appeared at (%.2f, %.2f) after %s, outside %s" % ((turtle,) + tuple(place) + (action, where))
    if index == 0:
        return "%s was already at (%.2f, %.2f) when %s began, outside %s" % ((turtle,) + tuple(place) +
                                                                               (action, where))
    return "%s left %s at (%.2f, %.2f), about %.1f s after %s" % (
        (turtle, where) + tuple(place) + (index * TICK, "it appeared (after %s)" % action if appeared else action))


def pen_colour(state: StepState, p: Dict, where: str) -> None:
    turtle = p.get("turtle") or "turtle1"
    wanted = tuple(int(p[k]) for k in ("r", "g", "b"))
    tolerance = int(p.get("tolerance") or 0)
    recorder = TopicRecorder("/%s/color_sensor" % turtle, Color)
    try:
        def seen() -> List[shapes.Rgb]:
            return [(m.r, m.g, m.b) for m in recorder.messages]
        if wait_for(lambda: any(shapes.colour_matches(c, wanted, tolerance) for c in seen()),
                    float(p.get("within") or 0.0), POLL_S):
            return
        colours = seen()
    finally:
        recorder.unregister()
    if not colours:
        raise course_error(where, "no colour on /%s/color_sensor: pen_colour needs the course's turtlesim (world: "
                                  "[turtlesim]) and a turtle named %s" % (turtle, turtle))
    place = turtles.watch(state, turtle).last
    raise failed("wrong_value", "the pen of %s draws %s here%s %s; the text asks (%d, %d, %d)" % (
        (turtle, shapes.colours_seen(colours), " (%.2f, %.2f)" % (place.x, place.y) if place else "",
         state.after_action()) + wanted))
