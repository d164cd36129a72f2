"""rqt_plot's live window: a matplotlib figure that redraws and scrolls while samples arrive.

Used only when a display exists and a GUI backend (Qt, else Tk) loads; otherwise the node
records and writes a PNG instead (course_graph.plot_figure).
"""
from __future__ import annotations

import os
import threading
from typing import Callable, Optional

from course_graph.plot_buffer import SampleBuffer
from course_graph.plot_figure import DPI, FIGURE_INCHES, add_lines, decorate
from course_graph.viewer import can_show

GUI_BACKENDS = ("QtAgg", "TkAgg")
REDRAW_MS = 100


def gui_backend() -> Optional[str]:
    """The first GUI backend matplotlib can open a window with, or None (no display, no Qt/Tk,
    or Qt told to draw offscreen)."""
    if not can_show():
        return None
    import matplotlib.pyplot as plt
    for name in GUI_BACKENDS:
        if name.startswith("Qt") and os.environ.get("QT_QPA_PLATFORM", "") in ("offscreen", "minimal"):
            continue
        try:
            plt.switch_backend(name)  # loads the toolkit and checks the display; ImportError if not
            return name
        except (ImportError, RuntimeError):
            continue
    return None


def run_window(buffer: SampleBuffer, clock: Callable[[], float], span: float, title: str,
               stop: threading.Event) -> None:
    """Show the window until it is closed or `stop` is set; the x axis shows the last `span` s."""
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation

    figure, axes = plt.subplots(figsize=FIGURE_INCHES, dpi=DPI)
    figure.canvas.manager.set_window_title(title)
    lines = add_lines(axes, buffer.snapshot())
    decorate(axes, title)

    def redraw(_frame: int) -> None:
        if stop.is_set():
            plt.close(figure)
            return
        for label, (times, values) in buffer.snapshot().items():
            lines[label].set_data(times, values)
        now = clock()
        axes.set_xlim(max(0.0, now - span), max(span, now))
        axes.relim()
        axes.autoscale_view(scalex=False)

    animation = FuncAnimation(figure, redraw, interval=REDRAW_MS, cache_frame_data=False)
    plt.show()
    del animation
