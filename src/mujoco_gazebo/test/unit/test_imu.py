import math

import numpy as np

from mujoco_gazebo.engine.frames import Pose, Twist, quat_from_rpy
from mujoco_gazebo.engine.imu import ImuModel

GRAVITY = (0.0, 0.0, -9.81)


def test_at_rest_reads_gravity_up_in_body_axes():
    imu = ImuModel()
    reading = imu.sample(0.0, Pose(), Twist(), GRAVITY)
    assert np.allclose(reading.linear_acceleration, [0, 0, 9.81]) and np.allclose(reading.angular_velocity, 0)
    # rolled a quarter turn: gravity's reaction lies along the body's +y
    rolled = Pose(orientation=quat_from_rpy(math.pi / 2, 0, 0))
    reading = imu.sample(0.1, rolled, Twist(), GRAVITY)
    assert np.allclose(reading.linear_acceleration, [0, 9.81, 0], atol=1e-9)
    assert np.allclose(reading.orientation, rolled.orientation)


def test_acceleration_is_the_velocity_difference_rotated_into_the_body():
    imu = ImuModel()
    yawed = Pose(orientation=quat_from_rpy(0, 0, math.pi / 2))  # body +x = world +y
    imu.sample(1.0, yawed, Twist([0, 0.0, 0]), GRAVITY)
    reading = imu.sample(1.5, yawed, Twist([0, 1.0, 0], [0, 0, 0.4]), GRAVITY)
    assert np.allclose(reading.linear_acceleration, [2.0, 0, 9.81])
    assert np.allclose(reading.angular_velocity, [0, 0, 0.4])


def test_no_acceleration_without_time_passing_and_after_reset():
    imu = ImuModel()
    imu.sample(1.0, Pose(), Twist([1, 0, 0]), GRAVITY)
    assert np.allclose(imu.sample(1.0, Pose(), Twist([5, 0, 0]), GRAVITY).linear_acceleration, [0, 0, 9.81])
    imu.reset()
    assert np.allclose(imu.sample(2.0, Pose(), Twist([9, 0, 0]), GRAVITY).linear_acceleration, [0, 0, 9.81])
