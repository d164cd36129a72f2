"""Rigid-body frame maths: poses as (position, unit quaternion w-x-y-z), composition,
inversion, relative poses and twists. Pure numpy, so the Gazebo reference_frame rules
can be unit-tested without MuJoCo or ROS."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

IDENTITY_QUAT = np.array([1.0, 0.0, 0.0, 0.0])


def normalize_quat(q: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z); a zero quaternion means 'no rotation', as Gazebo treats it."""
    q = np.asarray(q, dtype=float)
    scale = float(np.max(np.abs(q)))  # scaled first: squaring 1e200 would overflow to inf
    if not scale > 0.0 or not math.isfinite(scale) or scale * float(np.linalg.norm(q / scale)) < 1e-12:
        return IDENTITY_QUAT.copy()
    q = q / scale
    return q / float(np.linalg.norm(q))


def quat_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product a*b (apply b first, then a)."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz,
                     aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw])


def quat_conj(q: np.ndarray) -> np.ndarray:
    return np.array([q[0], -q[1], -q[2], -q[3]])


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    w, x, y, z = normalize_quat(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    return quat_to_matrix(q) @ np.asarray(v, dtype=float)


def quat_from_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Fixed-axis roll (x), pitch (y), yaw (z), as URDF, SDF and spawn_model's -R -P -Y use them."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return np.array([cr * cp * cy + sr * sp * sy,
                     sr * cp * cy - cr * sp * sy,
                     cr * sp * cy + sr * cp * sy,
                     cr * cp * sy - sr * sp * cy])


def yaw_of(q: np.ndarray) -> float:
    w, x, y, z = q
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


@dataclass
class Pose:
    """A frame: position (m) and orientation (unit quaternion w, x, y, z)."""

    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    orientation: np.ndarray = field(default_factory=lambda: IDENTITY_QUAT.copy())

    def __post_init__(self) -> None:
        self.position = np.asarray(self.position, dtype=float).reshape(3)
        self.orientation = normalize_quat(np.asarray(self.orientation, dtype=float).reshape(4))

    def compose(self, other: "Pose") -> "Pose":
        """self * other: `other` expressed in self's frame, returned in self's parent frame."""
        return Pose(self.position + rotate(self.orientation, other.position),
                    quat_mul(self.orientation, other.orientation))

    def inverse(self) -> "Pose":
        qi = quat_conj(self.orientation)
        return Pose(-rotate(qi, self.position), qi)

    def relative_to(self, ref: "Pose") -> "Pose":
        """This pose (world) expressed in the frame `ref` (world)."""
        return ref.inverse().compose(self)


@dataclass
class Twist:
    """Linear (m/s) and angular (rad/s) velocity, expressed in some frame's axes."""

    linear: np.ndarray = field(default_factory=lambda: np.zeros(3))
    angular: np.ndarray = field(default_factory=lambda: np.zeros(3))

    def __post_init__(self) -> None:
        self.linear = np.asarray(self.linear, dtype=float).reshape(3)
        self.angular = np.asarray(self.angular, dtype=float).reshape(3)


def twist_to_world(twist: Twist, ref: Pose) -> Twist:
    """A twist given in `ref`'s axes, rotated into world axes (Gazebo's set_model_state rule)."""
    return Twist(rotate(ref.orientation, twist.linear), rotate(ref.orientation, twist.angular))


def twist_relative(twist: Twist, ref_twist: Twist, ref: Pose) -> Twist:
    """World twist of an entity seen from a moving reference entity, in the reference's axes
    (Gazebo's get_model_state rule: velocity differences rotated into the reference frame)."""
    qi = quat_conj(ref.orientation)
    return Twist(rotate(qi, twist.linear - ref_twist.linear), rotate(qi, twist.angular - ref_twist.angular))


def all_finite(*arrays: np.ndarray) -> bool:
    return all(bool(np.all(np.isfinite(np.asarray(a, dtype=float)))) for a in arrays)
