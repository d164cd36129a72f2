import math

import pytest

from circles import PatrolRequest, Pose, farthest_off_circle, observed_centre, start_index


def drive(req: PatrolRequest, theta0: float, steps: int = 150, dt: float = 0.016):
    """Turtlesim's update from (req.x, req.y, theta0) at (req.vel, req.omega)."""
    x, y, th, poses = req.x, req.y, theta0, []
    for _ in range(steps):
        poses.append(Pose(x, y, th))
        th += req.omega * dt
        x += math.cos(th) * req.vel * dt
        y += math.sin(th) * req.vel * dt
    return poses


@pytest.mark.parametrize("req", [PatrolRequest(1.0, 1.0, 3.0, 3.0, 1.57), PatrolRequest(1.5, -1.0, 8.0, 8.0, -1.0)])
def test_patrol_from_the_start_pose_is_on_the_requested_circle(req):
    poses = drive(req, req.theta)
    centre = observed_centre(poses, req)
    assert math.dist(centre, req.centre()) < 0.05
    assert farthest_off_circle(poses, req) < 0.05
    assert start_index([Pose(0, 0, 0)] + poses, req) == 1


def test_ignored_heading_moves_the_centre():
    req = PatrolRequest(1.0, 1.0, 3.0, 3.0, 1.57)
    poses = drive(req, 0.0)
    assert math.dist(observed_centre(poses, req), req.centre()) > 1.0
    assert farthest_off_circle(poses, req) > 0.5


def test_centre_and_radius():
    req = PatrolRequest(2.0, -1.0, 5.0, 5.0, 0.0)
    assert req.radius() == 2.0
    assert req.centre() == pytest.approx((5.0, 3.0))
    assert start_index([Pose(1, 1, 0)], req) is None
