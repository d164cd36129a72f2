import math

import pytest

from turtle_tf2.geometry import euler_from_quaternion, pose_to_transform, quaternion_from_euler


def test_yaw_only_quaternion():
    x, y, z, w = quaternion_from_euler(0.0, 0.0, math.pi / 2)
    assert (x, y) == (0.0, 0.0)
    assert z == pytest.approx(math.sqrt(0.5))
    assert w == pytest.approx(math.sqrt(0.5))


@pytest.mark.parametrize("rpy", [(0.0, 0.0, 0.0), (3.14, 0.0, 0.0), (0.3, -0.7, 2.5), (-1.0, 0.2, -3.0)])
def test_euler_round_trip(rpy):
    assert euler_from_quaternion(quaternion_from_euler(*rpy)) == pytest.approx(rpy, abs=1e-9)


def test_static_example_roll_of_pi():
    # static_transform_publisher 0 0 3 0 0 3.14 A B: yaw 0, pitch 0, roll 3.14
    q = quaternion_from_euler(3.14, 0.0, 0.0)
    assert q[0] == pytest.approx(math.sin(1.57))
    assert q[3] == pytest.approx(math.cos(1.57))


def test_pose_to_transform():
    frame = pose_to_transform(5.5, 2.0, math.pi)
    assert frame.translation == (5.5, 2.0, 0.0)
    assert euler_from_quaternion(frame.rotation)[2] == pytest.approx(math.pi)


@pytest.mark.parametrize("bad", [(math.nan, 1.0, 0.0), (1.0, math.inf, 0.0), (1.0, 1.0, -math.inf)])
def test_pose_to_transform_refuses_non_finite(bad):
    with pytest.raises(ValueError, match="non-finite"):
        pose_to_transform(*bad)


def test_zero_quaternion_is_refused():
    with pytest.raises(ValueError):
        euler_from_quaternion((0.0, 0.0, 0.0, 0.0))
