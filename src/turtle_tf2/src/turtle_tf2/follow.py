"""The follow steering law: from where the leader is, seen from the follower, to a velocity.

The follower looks up the leader's frame expressed in its own frame (tf2
lookup_transform(follower, leader)), so (dx, dy) is "ahead" and "to the left".
It turns toward the leader in proportion to the bearing and drives forward in
proportion to the distance (the course text's law: 1.0 * atan2, 0.5 * distance).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple


@dataclass(frozen=True)
class FollowGains:
    """Proportional gains of the law; the defaults are the course text's."""

    rotation: float = 1.0
    forward: float = 0.5
    # Closer than this the follower stops (avoids spinning on atan2 noise at the leader).
    stop_distance: float = 0.05

    def __post_init__(self) -> None:
        for name in ("rotation", "forward", "stop_distance"):
            value = getattr(self, name)
            if not math.isfinite(value) or value < 0.0:
                raise ValueError("gain %s must be finite and >= 0, got %r" % (name, value))


class VelocityCommand(NamedTuple):
    """Forward speed (m/s, twist linear.x) and turn rate (rad/s, twist angular.z)."""

    linear: float
    angular: float


def steer(dx: float, dy: float, gains: FollowGains = FollowGains()) -> VelocityCommand:
    """Velocity that brings the follower toward a leader at (dx, dy) in the follower's frame."""
    if not (math.isfinite(dx) and math.isfinite(dy)):
        raise ValueError("leader offset is not finite: dx=%r dy=%r" % (dx, dy))
    distance = math.hypot(dx, dy)
    if distance < gains.stop_distance:
        return VelocityCommand(0.0, 0.0)
    return VelocityCommand(gains.forward * distance, gains.rotation * math.atan2(dy, dx))
