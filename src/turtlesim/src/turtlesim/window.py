"""The turtlesim window, shown when a display is present: paints the rendered canvas."""
from __future__ import annotations

from typing import Callable

from PyQt5.QtGui import QImage, QPainter
from PyQt5.QtWidgets import QWidget


class CanvasWindow(QWidget):
    """A fixed-size widget repainted from `render()` (paths plus turtles)."""

    def __init__(self, render: Callable[[], QImage]) -> None:
        super().__init__()
        self._render = render

    def paintEvent(self, _event) -> None:  # noqa: N802 (Qt's name)
        painter = QPainter(self)
        painter.drawImage(0, 0, self._render())
        painter.end()
