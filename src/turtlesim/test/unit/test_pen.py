"""set_pen semantics: off lifts only; width 0 keeps the width."""
from turtlesim.pen import Pen


def test_default_pen():
    assert (Pen().rgb, Pen().width, Pen().on) == ((179, 184, 255), 3, True)


def test_set_colour_and_width():
    assert Pen().set(255, 0, 0, 5, 0) == Pen(255, 0, 0, 5, True)


def test_width_zero_keeps_width():
    assert Pen(1, 2, 3, 7, True).set(255, 0, 0, 0, 0).width == 7


def test_off_lifts_pen_and_changes_nothing_else():
    pen = Pen(1, 2, 3, 7, True).set(255, 255, 255, 1, 1)
    assert pen == Pen(1, 2, 3, 7, False)


def test_putting_pen_down_again():
    assert Pen().set(0, 0, 0, 0, 1).set(10, 20, 30, 0, 0) == Pen(10, 20, 30, 3, True)
