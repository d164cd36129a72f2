"""Differential-drive kinematics and wheel odometry (the maths of gazebo_ros_diff_drive),
free of MuJoCo and ROS so it can be unit-tested."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Tuple


@dataclass
class DiffDriveGeometry:
    wheel_separation: float = 0.160   # m (TurtleBot3 Burger)
    wheel_radius: float = 0.033       # m
    max_linear: float = 0.22          # m/s (TurtleBot3 Burger limit)
    max_angular: float = 2.84         # rad/s


def clamp(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))


def wheel_speeds(geom: DiffDriveGeometry, linear: float, angular: float) -> Tuple[float, float]:
    """Body twist (m/s, rad/s), clamped to the robot's limits -> (left, right) wheel rates in rad/s."""
    v = clamp(linear, geom.max_linear)
    w = clamp(angular, geom.max_angular)
    half = geom.wheel_separation / 2.0
    return (v - w * half) / geom.wheel_radius, (v + w * half) / geom.wheel_radius


def body_twist(geom: DiffDriveGeometry, left_rate: float, right_rate: float) -> Tuple[float, float]:
    """Wheel rates (rad/s) -> body twist (m/s, rad/s)."""
    vl, vr = left_rate * geom.wheel_radius, right_rate * geom.wheel_radius
    return (vl + vr) / 2.0, (vr - vl) / geom.wheel_separation


class WheelOdometry:
    """Integrates wheel angle increments into a planar pose (x, y, yaw) in the odom frame,
    with the exact arc update (straight-line limit when the heading does not change)."""

    def __init__(self, geom: DiffDriveGeometry) -> None:
        self.geom = geom
        self.reset()

    def reset(self) -> None:
        self.x = self.y = self.yaw = 0.0
        self.linear = self.angular = 0.0
        self._last: Tuple[float, float] | None = None

    def update(self, left_angle: float, right_angle: float, dt: float) -> None:
        """Feed the current wheel joint angles (rad); the first call only sets the reference."""
        if self._last is None or dt <= 0:
            self._last = (left_angle, right_angle)
            return
        dl = (left_angle - self._last[0]) * self.geom.wheel_radius
        dr = (right_angle - self._last[1]) * self.geom.wheel_radius
        self._last = (left_angle, right_angle)
        ds, dyaw = (dl + dr) / 2.0, (dr - dl) / self.geom.wheel_separation
        if abs(dyaw) < 1e-9:
            self.x += ds * math.cos(self.yaw + dyaw / 2)
            self.y += ds * math.sin(self.yaw + dyaw / 2)
        else:
            radius = ds / dyaw
            self.x += radius * (math.sin(self.yaw + dyaw) - math.sin(self.yaw))
            self.y -= radius * (math.cos(self.yaw + dyaw) - math.cos(self.yaw))
        self.yaw = math.atan2(math.sin(self.yaw + dyaw), math.cos(self.yaw + dyaw))
        self.linear, self.angular = ds / dt, dyaw / dt
