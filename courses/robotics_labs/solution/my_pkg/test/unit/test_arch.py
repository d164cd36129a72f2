import math

import pytest

from my_pkg.arch import ArchError, ArchProgress, check_angle, positive_setting, wrap


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -0.1, 7.0])
def test_bad_angles_are_refused(bad):
    with pytest.raises(ArchError, match="range"):
        check_angle(bad)


def test_wrap_matches_turtlesim():
    assert wrap(math.pi) == pytest.approx(-math.pi)
    assert wrap(3 * math.pi / 2) == pytest.approx(-math.pi / 2)


def feed_until_done(progress, step=0.008, start=0.0):
    theta, n = start, 0
    progress.update(wrap(theta))
    while not progress.done and n < 10000:
        theta += step
        progress.update(wrap(theta))
        n += 1
    return theta


def test_stops_near_target():
    p = ArchProgress(1.5, 0.02)
    assert 1.48 <= feed_until_done(p) <= 1.5


def test_full_circle_is_not_zero():
    p = ArchProgress(2 * math.pi, 0.02)
    assert not p.update(0.0)
    assert feed_until_done(p) > 6.2


def test_zero_arch_is_done_at_once():
    assert ArchProgress(0.0).update(0.3)


def test_a_non_finite_heading_does_not_poison_the_progress():
    p = ArchProgress(1.0, 0.02)
    p.update(0.0)
    assert not p.update(float("nan"))
    assert not p.update(float("inf"))
    assert p.update(1.0)  # was never done: the sum had become NaN


@pytest.mark.parametrize("value", ["abc", None, float("nan"), float("inf"), -1.0, 0, [1]])
def test_bad_settings_fall_back_to_the_default_with_a_reason(value):
    number, problem = positive_setting("~linear_speed", value, 1.0)
    assert number == 1.0
    assert "~linear_speed must be a finite number > 0" in problem


@pytest.mark.parametrize("value", [2, "0.5", 1e-3])
def test_good_settings_are_kept(value):
    assert positive_setting("~threshold", value, 0.02) == (float(value), "")
