"""rqt_plot's picture: a line per field path over time, drawn with Debian's matplotlib.

Writing a file uses matplotlib's Agg canvas directly (no pyplot, no GUI backend), so it works on
a headless machine and never depends on which backend a display would pick.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, Mapping

from course_graph.plot_buffer import Series

FIGURE_INCHES = (8.0, 5.0)
DPI = 100
PNG_SIZE_PX = (int(FIGURE_INCHES[0] * DPI), int(FIGURE_INCHES[1] * DPI))
TIME_LABEL = "time (s since start)"
VALUE_LABEL = "value"


def add_lines(axes: Any, series: Mapping[str, Series]) -> Dict[str, Any]:
    """A line per label, in order (colours C0, C1, ... follow it), even for empty series."""
    return {label: axes.plot(times, values, label=label, linewidth=1.5)[0]
            for label, (times, values) in series.items()}


def decorate(axes: Any, title: str) -> None:
    axes.set_xlabel(TIME_LABEL)
    axes.set_ylabel(VALUE_LABEL)
    axes.set_title(title)
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best", fontsize="small")


def check_format(path: Path) -> None:
    """ValueError unless matplotlib can write a file with this name's suffix (none means PNG)."""
    from matplotlib.backend_bases import FigureCanvasBase
    suffix = path.suffix.lstrip(".").lower()
    formats = FigureCanvasBase.get_supported_filetypes()
    if suffix and suffix not in formats:
        raise ValueError("matplotlib cannot write .%s files (it writes %s)" % (suffix, ", ".join(sorted(formats))))


def save_figure(series: Mapping[str, Series], path: Path, title: str) -> None:
    """Write the whole recording; a .png is PNG_SIZE_PX pixels (.svg and .pdf work too)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=FIGURE_INCHES, dpi=DPI)
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    add_lines(axes, series)
    decorate(axes, title)
    figure.tight_layout()
    figure.savefig(str(path), dpi=DPI)
