from mybot_color_core.regions import (BOTTOM, DEFAULT_BACKGROUND, ENTER, LEAVE, LEFT, SIDE_BACKGROUNDS, TOP,
                                      CornerWatcher, SideWatcher, in_corner, nearest_side)


def test_corners_need_two_sides():
    assert in_corner(1.0, 1.0, 2.0)
    assert in_corner(10.5, 10.5, 2.0)
    assert not in_corner(1.0, 5.5, 2.0)
    assert not in_corner(5.5, 5.5, 2.0)


def test_corner_watcher_reports_only_changes():
    w = CornerWatcher(2.0)
    events = [w.update(x, 1.0) for x in (5.0, 3.0, 1.9, 1.5, 1.0, 2.5, 3.0)]
    assert events == [None, None, ENTER, None, None, LEAVE, None]


def test_nearest_side():
    assert nearest_side(0.5, 5.0, 1.0) == LEFT
    assert nearest_side(5.0, 0.2, 1.0) == BOTTOM
    assert nearest_side(5.0, 10.5, 1.0) == TOP
    assert nearest_side(5.0, 5.0, 1.0) is None


def test_side_watcher_gives_new_background_once():
    w = SideWatcher(1.0)
    assert w.update(5.0, 5.0) is None
    assert w.update(5.0, 0.5) == SIDE_BACKGROUNDS[BOTTOM]
    assert w.update(5.1, 0.4) is None
    assert w.update(5.0, 3.0) == DEFAULT_BACKGROUND
