"""One turtle: its pose, velocity command, pen and queued teleports, and what a tick does to it.

The physics are upstream turtlesim's: apply queued teleports, drop a command older
than COMMAND_TIMEOUT, turn, wrap theta into [-pi, pi), move holonomically, clamp to
the walls. Coordinates are world metres (y up); the wall report uses canvas
coordinates (y down) like upstream's warning.

Beyond upstream, no input can make the state non-finite or unpublishable: non-finite
numbers are refused, velocities are held within float32's range (the pose's field type),
a teleport lands at most MAX_REACH off the canvas, and every angle is wrapped exactly.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Tuple

from turtlesim.constants import COMMAND_TIMEOUT, FLOAT32_MAX, MAX_REACH, TWO_PI, WORLD_SIZE
from turtlesim.pen import Pen

Point = Tuple[float, float]
Segment = Tuple[Point, Point]


def wrap_angle(theta: float) -> float:
    """A finite theta wrapped into [-pi, pi), the range upstream's update keeps the orientation in.

    math.remainder is exact for every finite float; upstream's `theta - 2pi*floor((theta+pi)/2pi)`
    loses all precision past ~1e16 (1.6e16 gave -4.0).
    """
    wrapped = math.remainder(theta, TWO_PI)
    return -math.pi if wrapped >= math.pi else wrapped


def require_finite(what: str, **values: float) -> None:
    """Raise ValueError naming every non-finite value: bad input must not reach the pose."""
    bad = ["%s=%r" % (k, v) for k, v in values.items() if not math.isfinite(v)]
    if bad:
        raise ValueError("%s rejected: non-finite %s" % (what, ", ".join(bad)))


def saturate(value: float, limit: float = FLOAT32_MAX) -> float:
    """value held within [-limit, limit]."""
    return min(max(value, -limit), limit)


def in_reach(v: float) -> float:
    """A finite coordinate held within MAX_REACH of the canvas. Beyond the canvas the walls
    clamp it at the next tick anyway, so the turtle ends where upstream's would."""
    return min(max(v, -MAX_REACH), WORLD_SIZE + MAX_REACH)


def drawn_end(start: Point, end: Point) -> Point:
    """Where to draw a jump from `start` (in reach) to the finite `end` to: `end` itself, or
    if it lies out of reach, the point where the line leaves that zone (same direction, so
    the same pixels, with coordinates the painter handles)."""
    low, high = -MAX_REACH, WORLD_SIZE + MAX_REACH
    fraction = 1.0
    for origin, target in zip(start, end):
        if target > high:
            fraction = min(fraction, (high - origin) / (target - origin))
        elif target < low:
            fraction = min(fraction, (low - origin) / (target - origin))
    if fraction == 1.0:
        return end
    return (in_reach(start[0] + (end[0] - start[0]) * fraction),
            in_reach(start[1] + (end[1] - start[1]) * fraction))


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
        self.x, self.y = in_reach(x), in_reach(y)
        self.theta = wrap_angle(theta)
        self.vx = 0.0
        self.vy = 0.0
        self.w = 0.0
        self.last_command = -math.inf
        self.pen = Pen()
        self.icon = icon
        self._teleports: List[Teleport] = []

    def command(self, vx: float, vy: float, w: float, now: float) -> Optional[str]:
        """Take a velocity command (body frame x, y and yaw rate) received at wall time `now`.

        Non-finite values raise ValueError (the command is dropped). Values beyond float32's
        range are clamped to it, and the returned note says so (None when nothing was clamped).
        """
        require_finite("cmd_vel", linear_x=vx, linear_y=vy, angular_z=w)
        self.vx, self.vy, self.w = saturate(vx), saturate(vy), saturate(w)
        self.last_command = now
        clamped = ["%s=%r" % (k, v) for k, v in (("linear_x", vx), ("linear_y", vy), ("angular_z", w))
                   if abs(v) > FLOAT32_MAX]
        if clamped:
            return "cmd_vel: %s beyond float32's range, clamped to +-%g" % (", ".join(clamped), FLOAT32_MAX)
        return None

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

    def stop(self) -> None:
        """Drop the velocity command and any queued teleport (after a failed tick)."""
        self.vx = self.vy = self.w = 0.0
        self._teleports.clear()

    @property
    def linear_velocity(self) -> float:
        """The speed, within float32's range like every field of the pose."""
        return min(math.hypot(self.vx, self.vy), FLOAT32_MAX)

    def step(self, dt: float, now: float) -> StepResult:
        """Advance one tick of `dt` seconds at wall time `now`."""
        result = StepResult()
        for jump in self._teleports:
            start = (self.x, self.y)
            if jump.relative:
                self.theta = wrap_angle(self.theta + jump.b)
                end = (self.x + math.cos(self.theta) * jump.a, self.y + math.sin(self.theta) * jump.a)
            else:
                end = (jump.a, min(WORLD_SIZE, jump.b))
                self.theta = wrap_angle(jump.theta)
            self.x, self.y = in_reach(end[0]), in_reach(end[1])
            result.segments.append((start, drawn_end(start, end)))
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
