"""How a turtle moved between an action and now, judged from its poses (x, y, theta): for the
`turtle_moves` step, forward and backward along the heading it had before, left and right by the
heading's change (summed pose by pose, so a turn past pi still counts: course_milestones.turning);
for `stops_at` and `turns`, where it came to rest (at_rest: it moved, then its last poses are one
pose), its distance to a point, its heading, and the angle it turned in place."""
from __future__ import annotations

import math
from typing import NamedTuple, Optional, Sequence, Tuple

from course_milestones.steps.predicates import Verdict
from course_milestones.steps.shapes import turned
from course_milestones.turning import TurnTracker, wrap

DIRECTIONS = ("any", "forward", "backward", "left", "right")
Pose = Tuple[float, float, float]


class Movement(NamedTuple):
    """From the first pose to the last: along the first heading (m, forward positive), across it
    (m, left positive), the straight-line distance and the turn (rad, left positive)."""

    along: float
    across: float
    distance: float
    turned: float

    def words(self) -> str:
        return "moved %.2f m (%.2f m along its heading) and turned %.2f rad" % (self.distance, self.along,
                                                                              self.turned)


def movement(poses: Sequence[Pose]) -> Movement:
    """The movement over `poses` (at least one)."""
    (x0, y0, theta0), (x1, y1, _) = poses[0], poses[-1]
    dx, dy = x1 - x0, y1 - y0
    tracker = TurnTracker()
    for pose in poses:
        tracker.feed(pose[2])
    return Movement(dx * math.cos(theta0) + dy * math.sin(theta0), -dx * math.sin(theta0) + dy * math.cos(theta0),
                    math.hypot(dx, dy), tracker.turned)


def judge(poses: Sequence[Pose], direction: str, min_distance: float) -> Verdict:
    """Whether the poses show a move of at least `min_distance` (m, or rad for a turn) in `direction`."""
    if direction not in DIRECTIONS:
        return Verdict(False, "direction %r is not one of %s" % (direction, ", ".join(DIRECTIONS)))
    if not poses:
        return Verdict(False, "no pose was received")
    moved = movement(poses)
    reached = {
        "any": max(moved.distance, abs(moved.turned)),
        "forward": moved.along,
        "backward": -moved.along,
        "left": moved.turned,
        "right": -moved.turned,
    }[direction]
    asked = "%s %g %s" % ("turn" if direction in ("left", "right") else "move", min_distance,
                          "rad" if direction in ("left", "right") else "m")
    asked += "" if direction == "any" else " " + direction
    return Verdict(reached >= min_distance, "it %s; the text asks it to %s" % (moved.words(), asked))


# -- coming to rest ------------------------------------------------------------------------------------

MOVED_M = 0.05    # a turtle that went no farther, and turned less than MOVED_RAD, did not move
MOVED_RAD = 0.05
REST_M = 1e-4     # poses closer than this, and turned less than REST_RAD, are the same pose
REST_RAD = 1e-4


def went(poses: Sequence[Pose]) -> bool:
    """Whether the turtle moved or turned at all over `poses` (its farthest from the first place,
    or its heading's change summed pose by pose)."""
    if not poses:
        return False
    x0, y0 = poses[0][0], poses[0][1]
    far = max(math.hypot(p[0] - x0, p[1] - y0) for p in poses)
    return far >= MOVED_M or abs(turned(poses)) >= MOVED_RAD


def at_rest(poses: Sequence[Pose], still_poses: int) -> bool:
    """Whether the turtle moved and then stood still (neither moving nor turning) for its last
    `still_poses` poses."""
    if still_poses < 1 or len(poses) <= still_poses or not went(poses):
        return False
    last = poses[-still_poses - 1:]
    x, y, theta = last[0]
    return all(math.hypot(p[0] - x, p[1] - y) <= REST_M and abs(wrap(p[2] - theta)) <= REST_RAD for p in last)


def _heading_words(theta: float) -> str:
    return "heading %.2f rad" % theta


def judge_stop(poses: Sequence[Pose], x: Optional[float] = None, y: Optional[float] = None, tolerance: float = 0.1,
               heading: Optional[float] = None, heading_tolerance: float = 0.05) -> Verdict:
    """Whether the last of `poses` (where the turtle stands) is within `tolerance` m of (x, y) and
    its heading within `heading_tolerance` rad of `heading` (either may be None: not judged)."""
    if not poses:
        return Verdict(False, "no pose was received")
    px, py, theta = poses[-1]
    place = "(%.2f, %.2f), %s" % (px, py, _heading_words(theta))
    wrong = []
    if x is not None and y is not None:
        off = math.hypot(px - x, py - y)
        if not off <= tolerance:
            wrong.append("%.2f m from (%g, %g), where the text puts it (within %g m)" % (off, x, y, tolerance))
    if heading is not None:
        off = abs(wrap(theta - heading))
        if not off <= heading_tolerance:
            wrong.append("its heading %.2f rad off the text's %g rad (within %g)" % (off, heading, heading_tolerance))
    if wrong:
        return Verdict(False, "it stands at %s: %s" % (place, "; ".join(wrong)))
    return Verdict(True, "it stands at %s" % place)


def _way(angle: float) -> str:
    return "left" if angle > 0 else "right" if angle < 0 else ""


def judge_turn(poses: Sequence[Pose], angle: float, tolerance: float = 0.05, drift: float = 0.05,
               either_way: bool = False) -> Verdict:
    """Whether `poses` show a turn in place by `angle` (rad, left positive; either way with
    `either_way`) within `tolerance` rad, the position never farther than `drift` m from where it
    began."""
    if not poses:
        return Verdict(False, "no pose was received")
    turn = turned(poses)
    x0, y0 = poses[0][0], poses[0][1]
    farthest = max(poses, key=lambda p: math.hypot(p[0] - x0, p[1] - y0))
    away = math.hypot(farthest[0] - x0, farthest[1] - y0)
    did = "it turned %.2f rad%s" % (abs(turn), " " + _way(turn) if abs(turn) >= 0.005 else "")
    asked = "%g rad%s" % (abs(angle), " either way" if either_way else " " + _way(angle) if angle else "")
    off = abs(abs(turn) - abs(angle)) if either_way else abs(turn - angle)
    if not off <= tolerance:
        return Verdict(False, "%s; the text asks a turn of %s (within %g rad)" % (did, asked, tolerance))
    if not away <= drift:
        return Verdict(False, "%s, but it moved %.2f m from (%.2f, %.2f), at (%.2f, %.2f): a turn in place stays "
                              "within %g m" % (did, away, x0, y0, farthest[0], farthest[1], drift))
    return Verdict(True, "%s in place (it moved %.2f m at most)" % (did, away))
