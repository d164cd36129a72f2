"""How far a turtle has turned, from the stream of its headings.

turtlesim wraps theta into [-pi, pi), so an arch of more than pi crosses the wrap. The arch
milestone sums the wrapped change between consecutive poses instead of comparing raw headings,
so "turned 3.8 rad" and "turned past the target" are read the same way for every student.
"""
from __future__ import annotations

import math
from typing import Optional


def wrap(angle: float) -> float:
    """`angle` in [-pi, pi), the way turtlesim reports theta."""
    return angle - 2.0 * math.pi * math.floor((angle + math.pi) / (2.0 * math.pi))


def heading_error(theta: float, wanted: float) -> float:
    """Smallest absolute angle between two headings (radians, 0..pi)."""
    return abs(wrap(theta - wanted))


class TurnTracker:
    """Sums the signed heading change (left positive) over the headings it is fed."""

    def __init__(self) -> None:
        self.turned = 0.0
        self._last: Optional[float] = None

    def feed(self, theta: float) -> float:
        """Add one heading; the total turned so far."""
        if self._last is not None:
            self.turned += wrap(theta - self._last)
        self._last = theta
        return self.turned
