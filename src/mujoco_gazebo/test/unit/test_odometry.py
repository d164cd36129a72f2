import math

import numpy as np

from mujoco_gazebo.engine.diffdrive import DiffDriveGeometry, WheelOdometry
from mujoco_gazebo.engine.frames import Pose, Twist, quat_from_rpy, yaw_of
from mujoco_gazebo.engine.odometry import from_encoders, from_ground_truth


def test_encoder_estimate_is_planar_odometry():
    odo = WheelOdometry(DiffDriveGeometry())
    odo.update(0.0, 0.0, 0.0)
    odo.update(1.0, 2.0, 0.5)
    est = from_encoders(odo)
    assert np.allclose(est.pose.position, [odo.x, odo.y, 0.0])
    assert math.isclose(yaw_of(est.pose.orientation), odo.yaw, abs_tol=1e-12)
    assert np.allclose(est.linear, [odo.linear, 0, 0]) and np.allclose(est.angular, [0, 0, odo.angular])


def test_ground_truth_is_relative_to_spawn_pose_in_body_axes():
    origin = Pose([1.0, 2.0, 0.0], quat_from_rpy(0, 0, math.pi / 2))
    # facing world -x (a quarter turn left of the spawn heading), one metre along the spawn's +x
    pose = Pose([1.0, 3.0, 0.01], quat_from_rpy(0, 0, math.pi))
    twist = Twist([-0.2, 0.05, 0.3], [0.1, 0.2, 0.5])  # world axes
    est = from_ground_truth(pose, twist, origin)
    assert np.allclose(est.pose.position, [1.0, 0.0, 0.01])
    assert math.isclose(yaw_of(est.pose.orientation), math.pi / 2)
    # in the base's axes (+x = world -x): forward 0.2, sideways -0.05; z components dropped
    assert np.allclose(est.linear, [0.2, -0.05, 0.0]) and np.allclose(est.angular, [0.0, 0.0, 0.5])


def test_ground_truth_at_spawn_pose_is_origin():
    origin = Pose([0.5, -0.5, 0.0], quat_from_rpy(0, 0, 0.3))
    est = from_ground_truth(origin, Twist(), origin)
    assert np.allclose(est.pose.position, 0.0) and np.allclose(est.pose.orientation, [1, 0, 0, 0])
