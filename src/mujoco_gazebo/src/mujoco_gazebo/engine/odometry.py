"""What gazebo_ros_diff_drive publishes as odometry, as plain numbers: from the wheel encoders
(odometrySource encoder) or from the ground truth relative to the spawn pose (odometrySource
world, the default). No MuJoCo, no ROS: the plugin turns an OdometryEstimate into a message."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .diffdrive import WheelOdometry
from .frames import Pose, Twist, quat_conj, quat_from_rpy, rotate


@dataclass(frozen=True)
class OdometryEstimate:
    """Pose of the base in the odom frame and its twist in the base's own axes."""

    pose: Pose
    linear: np.ndarray     # m/s, body axes
    angular: np.ndarray    # rad/s, body axes


def from_encoders(odometry: WheelOdometry) -> OdometryEstimate:
    """The integrated wheel odometry: planar pose (z = 0), forward speed and yaw rate only."""
    pose = Pose(np.array([odometry.x, odometry.y, 0.0]), quat_from_rpy(0.0, 0.0, odometry.yaw))
    return OdometryEstimate(pose, np.array([odometry.linear, 0.0, 0.0]), np.array([0.0, 0.0, odometry.angular]))


def from_ground_truth(pose: Pose, twist: Twist, origin: Pose) -> OdometryEstimate:
    """The base's world pose relative to `origin` (where it was spawned) and its world twist
    rotated into the base's axes, kept planar as the plugin reports it (vx, vy, wz)."""
    inverse = quat_conj(pose.orientation)
    linear, angular = rotate(inverse, twist.linear), rotate(inverse, twist.angular)
    return OdometryEstimate(pose.relative_to(origin), np.array([linear[0], linear[1], 0.0]),
                            np.array([0.0, 0.0, angular[2]]))
