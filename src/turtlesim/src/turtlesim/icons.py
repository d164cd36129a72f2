"""Our own turtle drawings: a top view of a turtle facing +x, one shell colour per variant."""
from __future__ import annotations

from typing import List, Optional, Tuple

from PyQt5.QtCore import QPointF, QRectF, Qt
from PyQt5.QtGui import QBrush, QColor, QImage, QPainter, QPen, QPolygonF

from turtlesim.constants import METER_PX

SHELL_COLOURS: List[Tuple[int, int, int]] = [
    (46, 139, 87), (34, 120, 160), (160, 82, 45), (128, 128, 0),
    (95, 75, 139), (205, 133, 63), (47, 79, 79), (178, 34, 34),
]
SKIN = (154, 205, 50)
OUTLINE = (30, 40, 20)


def draw_turtle_icon(shell: Tuple[int, int, int], size: int = METER_PX) -> QImage:
    """A size x size transparent image of a turtle seen from above, head towards +x."""
    image = QImage(size, size, QImage.Format_ARGB32_Premultiplied)
    image.fill(Qt.transparent)
    painter = QPainter(image)
    painter.setRenderHint(QPainter.Antialiasing)
    painter.scale(size / 45.0, size / 45.0)
    outline = QPen(QColor(*OUTLINE), 1.2)
    skin = QBrush(QColor(*SKIN))
    painter.setPen(outline)
    painter.setBrush(skin)
    for cx, cy in ((29, 9), (29, 36), (13, 10), (13, 35)):  # flippers
        painter.drawEllipse(QPointF(cx, cy), 5.5, 4.0)
    painter.drawPolygon(QPolygonF([QPointF(7, 20.5), QPointF(2, 22.5), QPointF(7, 24.5)]))  # tail
    painter.drawEllipse(QPointF(38, 22.5), 5.5, 4.5)  # head
    painter.setBrush(QBrush(QColor(*shell)))
    painter.drawEllipse(QRectF(7, 9, 28, 27))  # shell
    painter.setPen(QPen(QColor(*shell).darker(160), 1.4))
    painter.setBrush(Qt.NoBrush)
    painter.drawEllipse(QRectF(14, 15.5, 14, 14))  # scute pattern
    for (x0, y0), (x1, y1) in (((14, 22.5), (8, 22.5)), ((28, 22.5), (34, 22.5)),
                               ((21, 15.5), (21, 10)), ((21, 29.5), (21, 35))):
        painter.drawLine(QPointF(x0, y0), QPointF(x1, y1))
    painter.setPen(Qt.NoPen)
    painter.setBrush(QBrush(QColor(0, 0, 0)))
    painter.drawEllipse(QPointF(40, 20.5), 1.0, 1.0)  # eyes
    painter.drawEllipse(QPointF(40, 24.5), 1.0, 1.0)
    painter.end()
    return image


class IconSet:
    """The turtle images, each drawn the first time it is shown (not at start-up, where time
    counts); a turtle keeps the index it was given at spawn."""

    def __init__(self) -> None:
        self._images: List[Optional[QImage]] = [None] * len(SHELL_COLOURS)

    def __len__(self) -> int:
        return len(self._images)

    def image(self, index: int) -> QImage:
        """The icon for `index` (taken modulo the number of icons)."""
        index %= len(self._images)
        if self._images[index] is None:
            self._images[index] = draw_turtle_icon(SHELL_COLOURS[index])
        return self._images[index]
