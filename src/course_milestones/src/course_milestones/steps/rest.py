"""The steps that judge where a turtle comes to rest after the last action, on the course's own
turtlesim: `stops_at` (its place and heading once it stands still: a motion's end, a goal reached
within a distance, a spawned turtle's place) and `turns` (the angle it turned in place). A turtle
is at rest once it moved and then stood still, neither moving nor turning, for `still` seconds
of its poses (turtlesim sends one every TICK); the judging is steps.motion, here the waiting and
the failure's sentence."""
from __future__ import annotations

import math
from typing import Dict, List, Tuple

from turtlesim.constants import TICK

from course_milestones.steps import drawing, motion
from course_milestones.steps.state import StepState, course_error, failed
from course_checks.waiting import wait_for


def _rested(state: StepState, p: Dict, where: str) -> Tuple[str, List[motion.Pose], bool]:
    """The turtle, its poses since the last action once it came to rest (or `within` passed), and
    whether it came to rest."""
    turtle = p.get("turtle") or "turtle1"
    still, within = float(p.get("still") or 0.0), float(p.get("within") or 0.0)
    if still <= 0:
        raise course_error(where, "still: %g s; the seconds at rest are more than 0" % still)
    count = max(1, int(math.ceil(still / TICK)))
    since = drawing.poses_since_action(state, turtle)
    if not since():
        raise drawing.no_pose(turtle)
    rested = wait_for(lambda: motion.at_rest(since(), count), within, drawing.POLL_S)
    return turtle, since(), bool(rested)


def _number(p: Dict, key: str):
    return float(p[key]) if p.get(key) is not None else None


def stops_at(state: StepState, p: Dict, where: str) -> None:
    x, y, heading = _number(p, "x"), _number(p, "y"), _number(p, "heading")
    if (x is None) != (y is None) or (x is None and heading is None):
        raise course_error(where, "stops_at takes x and y (the point), heading, or all three")
    turtle, poses, rested = _rested(state, p, where)
    verdict = motion.judge_stop(poses, x, y, float(p.get("tolerance") or 0.0), heading,
                                float(p.get("heading_tolerance") or 0.0))
    moved = motion.went(poses)
    if moved and not rested:
        raise failed("not_moving", "%s had not come to rest %g s %s: %s" % (
            turtle, float(p.get("within") or 0.0), state.after_action(), verdict.text.replace("it stands", "it was",
                                                                                             1)))
    if verdict.holds:
        return
    raise failed("not_moving", "%s %s: %s%s" % (turtle, state.after_action(), verdict.text,
                                                "" if moved else " (it did not move)"))


def turns(state: StepState, p: Dict, where: str) -> None:
    angle = float(p.get("angle") or 0.0)
    if angle == 0:
        raise course_error(where, "angle 0: a turn is by an angle other than 0 rad")
    turtle, poses, rested = _rested(state, p, where)
    verdict = motion.judge_turn(poses, angle, float(p.get("tolerance") or 0.0), float(p.get("drift") or 0.0),
                                bool(p.get("either_way")))
    if not motion.went(poses):
        raise failed("not_moving", "%s %s: it did not turn (%s)" % (turtle, state.after_action(), verdict.text))
    if not rested:
        raise failed("not_moving", "%s had not come to rest %g s %s: so far %s" % (
            turtle, float(p.get("within") or 0.0), state.after_action(), verdict.text))
    if verdict.holds:
        return
    raise failed("not_moving", "%s %s: %s" % (turtle, state.after_action(), verdict.text))
