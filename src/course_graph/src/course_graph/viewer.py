"""Show a PNG in a window when a display exists (the headless tools only write files)."""
from __future__ import annotations

import os
import sys


def can_show() -> bool:
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def show_png(path: str, title: str) -> None:
    """Open a window with the picture and return when it is closed."""
    from PyQt5.QtGui import QPixmap
    from PyQt5.QtWidgets import QApplication, QLabel, QScrollArea

    app = QApplication(sys.argv[:1])
    label = QLabel()
    label.setPixmap(QPixmap(path))
    view = QScrollArea()
    view.setWidget(label)
    view.setWindowTitle(title)
    view.resize(min(label.sizeHint().width() + 20, 1400), min(label.sizeHint().height() + 20, 900))
    view.show()
    app.exec_()
