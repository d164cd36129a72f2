import math

import numpy as np

from mujoco_gazebo.engine.frames import Pose, Twist, quat_from_rpy, twist_relative, twist_to_world, yaw_of


def test_compose_then_relative_round_trip():
    a = Pose([1, 2, 3], quat_from_rpy(0.1, -0.2, 0.7))
    b = Pose([0.5, -1, 0.2], quat_from_rpy(0.3, 0.0, -1.2))
    world = a.compose(b)
    back = world.relative_to(a)
    assert np.allclose(back.position, b.position)
    assert np.isclose(abs(np.dot(back.orientation, b.orientation)), 1.0)


def test_yaw_rotation_moves_point():
    ref = Pose([1, 0, 0], quat_from_rpy(0, 0, math.pi / 2))
    p = ref.compose(Pose([1, 0, 0]))
    assert np.allclose(p.position, [1, 1, 0])
    assert math.isclose(yaw_of(p.orientation), math.pi / 2)


def test_zero_quaternion_means_identity():
    assert np.allclose(Pose([0, 0, 0], [0, 0, 0, 0]).orientation, [1, 0, 0, 0])


def test_twists_rotate_with_reference():
    ref = Pose([0, 0, 0], quat_from_rpy(0, 0, math.pi / 2))
    w = twist_to_world(Twist([1, 0, 0], [0, 0, 1]), ref)
    assert np.allclose(w.linear, [0, 1, 0]) and np.allclose(w.angular, [0, 0, 1])
    rel = twist_relative(Twist([0, 1, 0], [0, 0, 0]), Twist([0, 0, 0], [0, 0, 0]), ref)
    assert np.allclose(rel.linear, [1, 0, 0])
