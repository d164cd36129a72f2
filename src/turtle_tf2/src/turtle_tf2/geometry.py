"""Planar pose <-> rigid transform maths used by the broadcaster and tf2_echo.

Plain Python (no ROS) so the numbers are unit-tested: a turtle pose (x, y, theta)
becomes the transform world -> turtleN, i.e. a translation (x, y, 0) and a
rotation of theta about z, written as a unit quaternion (x, y, z, w).
"""
from __future__ import annotations

import math
from typing import NamedTuple, Tuple

Quaternion = Tuple[float, float, float, float]


class PlanarTransform(NamedTuple):
    """A frame placed on the plane: translation (x, y, 0) and yaw as a quaternion."""

    translation: Tuple[float, float, float]
    rotation: Quaternion


def quaternion_from_euler(roll: float, pitch: float, yaw: float) -> Quaternion:
    """Quaternion (x, y, z, w) of the fixed-axis rotation roll about x, pitch about y, yaw about z."""
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def euler_from_quaternion(q: Quaternion) -> Tuple[float, float, float]:
    """(roll, pitch, yaw) of a quaternion (x, y, z, w); the inverse of quaternion_from_euler.

    The quaternion is normalised first; pitch is clamped at +-pi/2 (gimbal lock).
    """
    x, y, z, w = q
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    if norm == 0.0 or not math.isfinite(norm):
        raise ValueError("not a rotation quaternion: %r" % (q,))
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    sin_pitch = max(-1.0, min(1.0, 2.0 * (w * y - z * x)))
    pitch = math.asin(sin_pitch)
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


def pose_to_transform(x: float, y: float, theta: float) -> PlanarTransform:
    """The transform world -> turtle for a turtlesim pose; rejects non-finite values."""
    if not all(math.isfinite(v) for v in (x, y, theta)):
        raise ValueError("pose has a non-finite value: x=%r y=%r theta=%r" % (x, y, theta))
    return PlanarTransform((float(x), float(y), 0.0), quaternion_from_euler(0.0, 0.0, theta))
