import math

from course_milestones.turning import TurnTracker, heading_error, wrap


def test_wrap_matches_turtlesim_range():
    assert wrap(math.pi) == -math.pi
    assert abs(wrap(4.0) - (4.0 - 2 * math.pi)) < 1e-12
    assert wrap(-0.5) == -0.5


def test_heading_error_across_the_wrap():
    assert abs(heading_error(-3.1, 3.1) - (2 * math.pi - 6.2)) < 1e-9
    assert heading_error(1.0, 1.0) == 0.0


def test_tracker_sums_through_the_wrap():
    tracker = TurnTracker()
    theta = 0.0
    for _ in range(400):  # 400 steps of 0.01 rad: 4 rad, crossing pi
        tracker.feed(wrap(theta))
        theta += 0.01
    assert abs(tracker.turned - 3.99) < 1e-6


def test_tracker_counts_right_turns_negative():
    tracker = TurnTracker()
    for theta in (0.0, -0.2, -0.4):
        tracker.feed(theta)
    assert abs(tracker.turned + 0.4) < 1e-12
