"""How a turtle moved between an action and now, judged from its poses (x, y, theta), for the
`turtle_moves` step: forward and backward along the heading it had before, left and right by the
heading's change (summed pose by pose, so a turn past pi still counts: course_milestones.turning)."""
from __future__ import annotations

import math
from typing import NamedTuple, Sequence, Tuple

from course_milestones.steps.predicates import Verdict
from course_milestones.turning import TurnTracker

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
