"""The draw_square tutorial's driver: side, stop, quarter turn, stop, repeat, from pose feedback."""
from __future__ import annotations

import math
from typing import Optional, Tuple

from turtlesim.turtle import wrap_angle


class SquareDriver:
    """Given each new pose, says which (linear, angular) velocity to command.

    Closed-loop on the pose: drive forward until `side` metres from the corner it
    started at, then turn in place until the heading is a quarter turn further.
    """

    def __init__(self, side: float = 2.0, speed: float = 1.0, turn_rate: float = 0.4,
                 tolerance: float = 1e-4) -> None:
        self.side = side
        self.speed = speed
        self.turn_rate = turn_rate
        self.tolerance = tolerance
        self.state = "forward"
        self.corners = 0
        self._start: Optional[Tuple[float, float]] = None
        self._goal_theta: Optional[float] = None

    def command(self, x: float, y: float, theta: float) -> Tuple[float, float]:
        if self.state == "forward":
            if self._start is None:
                self._start = (x, y)
            remaining = self.side - math.hypot(x - self._start[0], y - self._start[1])
            if remaining > self.tolerance:
                return (min(self.speed, max(remaining / 0.016, 0.0)), 0.0)
            self.state, self._start = "turn", None
            self._goal_theta = wrap_angle(theta + math.pi / 2.0)
        error = wrap_angle(self._goal_theta - theta)
        if abs(error) > self.tolerance:
            return (0.0, math.copysign(min(self.turn_rate, abs(error) / 0.016), error))
        self.state, self._goal_theta = "forward", None
        self.corners += 1
        return (0.0, 0.0)
