"""xwininfo's tree read as windows with titles and places on the screen."""
from course_testkit.xwindows import XWindow, is_viewable, largest_titled, parse_tree

TREE = '''
xwininfo: Window id: 0x4a7 (the root window) (has no name)

  Root window id: 0x4a7 (the root window) (has no name)
  Parent window id: 0x0 (none)
     11 children:
     0x60000d "turtle_tf2.rviz - RViz": ("rviz" "rviz")  1000x700+3+21  +610+21
        3 children:
        0x600109 "rviz": ("rviz" "rviz")  640x480+0+0  +610+21
     0xa00008 "turtlesim_node": ()  1x1+0+0  +0+0
     0x600006 (has no name): ()  604x415+0+0  +0+0
        0xa00006 "TurtleSim": ("turtlesim_node" "turtlesim_node")  500x500+3+21  +3+439
     0x80000d "Qt NET_WM User Time Window": ()  1x1+-1+-1  +508+438
'''


def test_the_tree_gives_each_named_window_its_absolute_place():
    windows = parse_tree(TREE)
    assert XWindow("0xa00006", "TurtleSim", 3, 439, 500, 500) in windows
    assert [w.title for w in windows].count("rviz") == 1
    assert all(w.title for w in windows)  # the unnamed frame is left out
    assert XWindow("0x80000d", "Qt NET_WM User Time Window", 508, 438, 1, 1) in windows


def test_the_largest_window_of_a_title_is_the_applications():
    windows = parse_tree(TREE)
    assert largest_titled(windows, "RViz").id == "0x60000d"
    assert largest_titled(windows, "turtlesim_node").width == 1
    assert largest_titled(windows, "rqt_plot") is None
    assert largest_titled(windows, "TurtleSim").box == (3, 439, 503, 939)


def test_only_a_mapped_window_is_viewable():
    stats = "  Width: 1000\n  Map State: %s\n  Override Redirect State: no\n"
    assert is_viewable(stats % "IsViewable")
    assert not is_viewable(stats % "IsUnMapped") and not is_viewable(stats % "IsUnviewable")
    assert not is_viewable("")
