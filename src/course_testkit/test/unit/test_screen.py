import ctypes
import ctypes.util
import json
import shutil

import pytest

from course_testkit.screen import VirtualDisplay, colour_stats, grab_screen


def test_uniform_image_is_blank():
    stats = colour_stats([(48, 48, 48)] * 1000)
    assert stats.distinct == 1 and stats.looks_blank()


def test_varied_image_is_not_blank_and_red_is_counted():
    pixels = [(i % 200, (i * 7) % 256, (i * 13) % 256) for i in range(4000)] + [(220, 30, 30)] * 50
    stats = colour_stats(pixels)
    assert not stats.looks_blank()
    assert stats.reddish >= 50


def test_mostly_one_colour_is_blank():
    pixels = [(0, 0, 0)] * 9990 + [(i, i, i) for i in range(1, 11)]
    assert colour_stats(pixels).looks_blank()


def test_no_pixels():
    assert colour_stats([]).looks_blank()


@pytest.mark.skipif(shutil.which("Xvfb") is None, reason="Xvfb not installed")
def test_virtual_display_starts_and_stops():
    display = VirtualDisplay(size=(320, 240))
    name = display.start()
    try:
        assert name.startswith(":") and name[1:].isdigit()
        assert display.process.poll() is None
    finally:
        display.stop()
    assert display.process is None


def paint_root_and_leave(display: str, rgb: int) -> None:
    """As the display's only client: set the root window's background to `rgb`, then disconnect."""
    x11 = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XDefaultRootWindow.restype = ctypes.c_ulong
    x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
    x11.XSetWindowBackground.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_ulong]
    x11.XClearWindow.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    connection = x11.XOpenDisplay(display.encode())
    assert connection, "could not connect to %s" % display
    root = x11.XDefaultRootWindow(connection)
    x11.XSetWindowBackground(connection, root, rgb)
    x11.XClearWindow(connection, root)
    x11.XCloseDisplay(connection)  # flushes the requests; the server has no client left


@pytest.mark.skipif(shutil.which("Xvfb") is None, reason="Xvfb not installed")
def test_virtual_display_does_not_reset_when_its_last_client_leaves(tmp_path):
    """A server that resets when its last client leaves refuses whoever connects meanwhile (the
    live rqt_plot window failed so, beside its screenshots). A reset also repaints the root
    window, which makes the reset visible: the red set by a client that left must stay."""
    with VirtualDisplay(size=(320, 240)) as display:
        paint_root_and_leave(display.display, 0xFF0000)
        stats = json.loads(grab_screen(display.display, str(tmp_path / "root.png")))
    assert stats["distinct"] == 1 and stats["reddish"] > 0, stats


def test_colour_share_counts_pixels_near_the_colour():
    from course_testkit.screen import colour_share
    pixels = [(69, 86, 255)] * 80 + [(75, 80, 250)] * 10 + [(0, 0, 0)] * 10
    assert colour_share(pixels, (69, 86, 255)) == 0.9
    assert colour_share(pixels, (69, 86, 255), tolerance=0) == 0.8
    assert colour_share([], (0, 0, 0)) == 0.0
