"""Lab 2 checkpoint 3 (002 section 5): is a turtle patrolling the circle its service call asked for?

A turtle driven with forward speed `vel` and turn rate `omega` from (x, y) heading theta runs on
the circle of radius |vel/omega| centred at (x - r sin theta, y + r cos theta), r = vel/omega. The
centre moves with the start heading, so a patrol that ignores theta circles somewhere else.
"""
from __future__ import annotations

import math
from typing import Iterable, List, NamedTuple, Optional, Sequence, Tuple

Point = Tuple[float, float]


class PatrolRequest(NamedTuple):
    """The five numbers of `rosservice call /<turtle>/patrol vel omega x y theta`."""

    vel: float
    omega: float
    x: float
    y: float
    theta: float

    def centre(self) -> Point:
        r = self.vel / self.omega
        return self.x - r * math.sin(self.theta), self.y + r * math.cos(self.theta)

    def radius(self) -> float:
        return abs(self.vel / self.omega)


class Pose(NamedTuple):
    x: float
    y: float
    theta: float


def start_index(poses: Sequence[Pose], request: PatrolRequest, tolerance: float = 0.25) -> Optional[int]:
    """Index of the first pose at the requested start point (after the teleport), or None."""
    for i, p in enumerate(poses):
        if math.hypot(p.x - request.x, p.y - request.y) < tolerance:
            return i
    return None


def observed_centre(poses: Iterable[Pose], request: PatrolRequest) -> Point:
    """The centre the turtle is circling, from its own positions and headings (the mean of the
    centres each pose implies at the requested vel/omega)."""
    r = request.vel / request.omega
    centres: List[Point] = [(p.x - r * math.sin(p.theta), p.y + r * math.cos(p.theta)) for p in poses]
    return (sum(c[0] for c in centres) / len(centres), sum(c[1] for c in centres) / len(centres))


def farthest_off_circle(poses: Iterable[Pose], request: PatrolRequest) -> float:
    """The largest distance of a pose from the requested circle."""
    cx, cy = request.centre()
    return max(abs(math.hypot(p.x - cx, p.y - cy) - request.radius()) for p in poses)
