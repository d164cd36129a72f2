"""What gazebo_ros_imu reads from a body, as plain numbers: orientation in the world frame,
angular velocity and linear acceleration in the body's axes, gravity included as an
accelerometer feels it (at rest it reads +9.81 up). The acceleration is the finite difference
of the body origin's world velocity between two samples. No MuJoCo, no ROS."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import numpy as np

from .frames import Pose, Twist, quat_conj, rotate


@dataclass(frozen=True)
class ImuReading:
    orientation: np.ndarray           # w, x, y, z (world)
    angular_velocity: np.ndarray      # rad/s, body axes
    linear_acceleration: np.ndarray   # m/s^2, body axes, gravity included


class ImuModel:
    """Turns successive (time, pose, twist) samples of one body into IMU readings."""

    def __init__(self) -> None:
        self._last: Optional[Tuple[float, np.ndarray]] = None

    def reset(self) -> None:
        self._last = None

    def sample(self, now: float, pose: Pose, twist: Twist, gravity: Sequence[float]) -> ImuReading:
        """The first sample (and one not later than the previous) has no motion acceleration."""
        acc = np.zeros(3)
        if self._last is not None and now > self._last[0]:
            acc = (twist.linear - self._last[1]) / (now - self._last[0])
        self._last = (now, twist.linear.copy())
        inverse = quat_conj(pose.orientation)
        return ImuReading(orientation=np.array(pose.orientation, dtype=float),
                          angular_velocity=rotate(inverse, twist.angular),
                          linear_acceleration=rotate(inverse, acc - np.asarray(gravity, dtype=float)))
