import shutil

import pytest

from course_testkit.screen import VirtualDisplay, colour_stats


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
