import math

from mujoco_gazebo.engine.diffdrive import DiffDriveGeometry, WheelOdometry, body_twist, wheel_speeds

BURGER = DiffDriveGeometry()


def test_wheel_speeds_round_trip_and_limits():
    left, right = wheel_speeds(BURGER, 0.1, 0.5)
    assert math.isclose(left, (0.1 - 0.5 * 0.08) / 0.033)
    v, w = body_twist(BURGER, left, right)
    assert math.isclose(v, 0.1) and math.isclose(w, 0.5)
    v, w = body_twist(BURGER, *wheel_speeds(BURGER, 5.0, -10.0))
    assert math.isclose(v, 0.22) and math.isclose(w, -2.84)


def test_odometry_straight_line():
    odo = WheelOdometry(BURGER)
    odo.update(0.0, 0.0, 0.0)
    odo.update(10.0, 10.0, 1.0)
    assert math.isclose(odo.x, 0.33) and abs(odo.y) < 1e-12 and abs(odo.yaw) < 1e-12
    assert math.isclose(odo.linear, 0.33)


def test_odometry_spin_in_place_and_arc():
    odo = WheelOdometry(BURGER)
    odo.update(0.0, 0.0, 0.0)
    quarter = (math.pi / 2) * 0.08 / 0.033  # wheel angle for a quarter turn in place
    odo.update(-quarter, quarter, 1.0)
    assert abs(odo.x) < 1e-9 and abs(odo.y) < 1e-9 and math.isclose(odo.yaw, math.pi / 2)
    arc = WheelOdometry(BURGER)
    arc.update(0.0, 0.0, 0.0)
    # a half circle of radius 0.5 m in many steps ends at (0, 1)
    r, n = 0.5, 200
    dl, dr = (r - 0.08) * math.pi / 0.033 / n, (r + 0.08) * math.pi / 0.033 / n
    for k in range(1, n + 1):
        arc.update(dl * k, dr * k, 0.01)
    assert abs(arc.x) < 1e-6 and math.isclose(arc.y, 1.0, rel_tol=1e-6)
