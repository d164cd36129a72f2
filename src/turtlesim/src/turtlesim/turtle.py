"""One turtle: its pose, velocity command, pen and queued teleports, and what a tick does to it.

The physics are upstream turtlesim's: apply queued teleports, drop a command older
than COMMAND_TIMEOUT, turn, wrap theta into [-pi, pi), move holonomically, clamp to
the walls. Coordinates are world metres (y up); the wall report uses canvas
coordinates (y down) like upstream's warning.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Tuple

from turtlesim.constants import COMMAND_TIMEOUT, TWO_PI, WORLD_SIZE
from turtlesim.pen import Pen

Point = Tuple[float, float]
Segment = Tuple[Point, Point]


def wrap_angle(theta: float) -> float:
    """theta wrapped into [-pi, pi), the way upstream wraps the orientation."""
    return theta - TWO_PI * math.floor((theta + math.pi) / TWO_PI)


def require_finite(what: str, **values: float) -> None:
    """Raise ValueError naming every non-finite value: bad input must not reach the pose."""
    bad = ["%s=%r" % (k, v) for k, v in values.items() if not math.isfinite(v)]
    if bad:
        raise ValueError("%s rejected: non-finite %s" % (what, ", ".join(bad)))


@dataclass
class Teleport:
    """A queued teleport: absolute (x, y, theta) or relative (linear, angular)."""

    relative: bool
    a: float
    b: float
    theta: float = 0.0


@dataclass
class StepResult:
    """What one tick did: path segments to draw, and the pre-clamp position if a wall was hit."""

    segments: List[Segment] = field(default_factory=list)
    clamped_from: Optional[Point] = None


class Turtle:
    """A turtle's state; `step` advances it by one tick."""

    def __init__(self, x: float, y: float, theta: float, icon: int = 0) -> None:
        require_finite("spawn", x=x, y=y, theta=theta)
        self.x = x
        self.y = y
        self.theta = theta
        self.vx = 0.0
        self.vy = 0.0
        self.w = 0.0
        self.last_command = -math.inf
        self.pen = Pen()
        self.icon = icon
        self._teleports: List[Teleport] = []

    def command(self, vx: float, vy: float, w: float, now: float) -> None:
        """Take a velocity command (body frame x, y and yaw rate) received at wall time `now`."""
        require_finite("cmd_vel", linear_x=vx, linear_y=vy, angular_z=w)
        self.vx, self.vy, self.w = vx, vy, w
        self.last_command = now

    def teleport_absolute(self, x: float, y: float, theta: float) -> None:
        """Queue a jump to (x, y, theta); it happens at the next tick."""
        require_finite("teleport_absolute", x=x, y=y, theta=theta)
        self._teleports.append(Teleport(False, x, y, theta))

    def teleport_relative(self, linear: float, angular: float) -> None:
        """Queue a turn by `angular`, then a move of `linear` along the new heading."""
        require_finite("teleport_relative", linear=linear, angular=angular)
        self._teleports.append(Teleport(True, linear, angular))

    def set_pen(self, r: int, g: int, b: int, width: int, off: int) -> None:
        self.pen = self.pen.set(r, g, b, width, off)

    @property
    def linear_velocity(self) -> float:
        return math.hypot(self.vx, self.vy)

    def step(self, dt: float, now: float) -> StepResult:
        """Advance one tick of `dt` seconds at wall time `now`."""
        result = StepResult()
        for jump in self._teleports:
            start = (self.x, self.y)
            if jump.relative:
                self.theta += jump.b
                self.x += math.cos(self.theta) * jump.a
                self.y += math.sin(self.theta) * jump.a
            else:
                self.x = jump.a
                self.y = min(WORLD_SIZE, jump.b)
                self.theta = jump.theta
            result.segments.append((start, (self.x, self.y)))
        self._teleports.clear()

        if now - self.last_command > COMMAND_TIMEOUT:
            self.vx = self.vy = self.w = 0.0

        start = (self.x, self.y)
        self.theta = wrap_angle(self.theta + self.w * dt)
        cos_t, sin_t = math.cos(self.theta), math.sin(self.theta)
        self.x += (cos_t * self.vx - sin_t * self.vy) * dt
        self.y += (sin_t * self.vx + cos_t * self.vy) * dt

        if not (0.0 <= self.x <= WORLD_SIZE and 0.0 <= self.y <= WORLD_SIZE):
            result.clamped_from = (self.x, WORLD_SIZE - self.y)
            self.x = min(max(self.x, 0.0), WORLD_SIZE)
            self.y = min(max(self.y, 0.0), WORLD_SIZE)
        if (self.x, self.y) != start:
            result.segments.append((start, (self.x, self.y)))
        return result
