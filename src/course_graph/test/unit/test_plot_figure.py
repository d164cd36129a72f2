import math

import pytest

from course_graph.plot_figure import PNG_SIZE_PX, check_format, save_figure
from course_graph.png_colours import colour_rows, png_size

TIMES = [i * 0.05 for i in range(61)]


def test_png_has_a_moving_line_per_series(tmp_path):
    path = tmp_path / "plot.png"
    series = {"/turtle1/pose/x": (TIMES, [5.5 + math.sin(t) for t in TIMES]),
              "/turtle1/pose/y": (TIMES, [5.5 - math.cos(t) for t in TIMES])}
    save_figure(series, path, "/turtle1/pose/x /turtle1/pose/y")
    assert png_size(str(path)) == PNG_SIZE_PX
    for colour in ("C0", "C1"):
        rows = colour_rows(str(path), colour).rows
        assert len(rows) > 100, colour


def test_flat_line_holds_few_rows(tmp_path):
    path = tmp_path / "flat.png"
    save_figure({"/a/x": (TIMES, [1.0] * len(TIMES))}, path, "flat")
    found = colour_rows(str(path), "C0")
    assert found.pixels > 100 and len(found.rows) < 10
    assert colour_rows(str(path), "C1").pixels == 0


def test_empty_series_still_write_a_picture(tmp_path):
    path = tmp_path / "empty.png"
    save_figure({"/a/x": ([], [])}, path, "nothing")
    assert png_size(str(path)) == PNG_SIZE_PX


def test_svg_by_suffix(tmp_path):
    path = tmp_path / "plot.svg"
    save_figure({"/a/x": (TIMES, TIMES)}, path, "svg")
    assert "<svg" in path.read_text()


def test_unknown_suffix_is_refused(tmp_path):
    check_format(tmp_path / "plot.png")
    check_format(tmp_path / "plot")
    with pytest.raises(ValueError, match="cannot write .xyz"):
        check_format(tmp_path / "plot.xyz")
