"""Drawing an arch: how far the turtle has turned, and when to stop.

The turtle drives forward while turning left; the arch is done when the heading has
turned through the requested angle (within a threshold). Turning is tracked as the sum
of wrapped heading changes, so 2*pi (a full circle) is not mistaken for 0.
"""
from __future__ import annotations

import math
from typing import Optional


class ArchError(ValueError):
    """The requested arch angle is not a number in [0, 2*pi]."""


def positive_setting(name: str, value: object, default: float) -> "tuple[float, str]":
    """A speed or threshold read from a parameter: the value when it is a finite number > 0,
    else the default and a sentence saying why (the node logs it and keeps running)."""
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        number = math.nan
    if math.isfinite(number) and number > 0:
        return number, ""
    return default, "%s must be a finite number > 0, got %r; using %s" % (name, value, default)


def check_angle(angle: float) -> float:
    if not math.isfinite(angle) or not 0.0 <= angle <= 2.0 * math.pi + 1e-6:
        raise ArchError("Angle must be in range [0, 2PI], got %r" % angle)
    return min(angle, 2.0 * math.pi)


def wrap(angle: float) -> float:
    """Into [-pi, pi), like turtlesim's orientation."""
    return angle - 2.0 * math.pi * math.floor((angle + math.pi) / (2.0 * math.pi))


class ArchProgress:
    """Accumulates the heading change from the first pose and says when the target is reached."""

    def __init__(self, target: float, threshold: float = 0.02) -> None:
        self.target = check_angle(target)
        self.threshold = threshold
        self.turned = 0.0
        self._last: Optional[float] = None

    def update(self, theta: float) -> bool:
        """Feed a heading; True once the turtle has turned to within the threshold of the target.

        A non-finite heading is skipped: one bad pose must not poison the sum for good.
        """
        if not math.isfinite(theta):
            return self.done
        if self._last is not None:
            self.turned += wrap(theta - self._last)
        self._last = theta
        return self.done

    @property
    def done(self) -> bool:
        return self.target - self.turned < self.threshold
