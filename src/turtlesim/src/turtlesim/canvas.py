"""The canvas: the path image the turtles draw on, its colour sensor, and rendered views.

Like upstream, paths live in their own image (turtles are not in it), so the colour
sensor reads only what was drawn; rendering composes paths and turtle icons.
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import Iterable, Sequence, Tuple

from PyQt5.QtCore import QLineF, QPointF, Qt
from PyQt5.QtGui import QColor, QImage, QPainter, QPen

from turtlesim.constants import CANVAS_PX, DEFAULT_BACKGROUND_RGB, METER_PX, WORLD_SIZE
from turtlesim.icons import IconSet
from turtlesim.pen import Pen
from turtlesim.turtle import Segment, Turtle

RGB = Tuple[int, int, int]


def to_pixel(x: float, y: float) -> QPointF:
    """World metres (y up) to canvas pixels (y down)."""
    return QPointF(x * METER_PX, (WORLD_SIZE - y) * METER_PX)


@lru_cache(maxsize=64)
def qpen(pen: Pen) -> QPen:
    """The Qt pen drawing with `pen` (made once per pen: the tick draws every turtle's path)."""
    return QPen(QColor(pen.r, pen.g, pen.b), pen.width)


class Canvas:
    """The 500x500 path image and the drawing operations on it."""

    def __init__(self, background: RGB = DEFAULT_BACKGROUND_RGB, icons: IconSet = None) -> None:
        self.path = QImage(CANVAS_PX, CANVAS_PX, QImage.Format_RGB32)
        self.icons = icons if icons is not None else IconSet()
        self.fill(background)

    def fill(self, rgb: RGB) -> None:
        """Wipe every path, painting the background colour."""
        self.path.fill(QColor(*rgb))

    def draw(self, strokes: Iterable[Tuple[Pen, Sequence[Segment]]]) -> None:
        """Draw each pen's segments (pens that are up draw nothing)."""
        painter = None
        for pen, segments in strokes:
            if not pen.on or not segments:
                continue
            if painter is None:
                painter = QPainter(self.path)
            painter.setPen(qpen(pen))
            for (x0, y0), (x1, y1) in segments:  # to_pixel, inlined: this runs per turtle per tick
                painter.drawLine(QLineF(x0 * METER_PX, (WORLD_SIZE - y0) * METER_PX,
                                        x1 * METER_PX, (WORLD_SIZE - y1) * METER_PX))
        if painter is not None:
            painter.end()

    def colour_at(self, x: float, y: float) -> RGB:
        """The path-image colour under world point (x, y): the turtle's colour sensor."""
        point = to_pixel(x, y)
        px = min(max(int(math.floor(point.x() + 0.5)), 0), CANVAS_PX - 1)
        py = min(max(int(math.floor(point.y() + 0.5)), 0), CANVAS_PX - 1)
        rgb = self.path.pixel(px, py)
        return ((rgb >> 16) & 0xFF, (rgb >> 8) & 0xFF, rgb & 0xFF)

    def render(self, turtles: Iterable[Turtle]) -> QImage:
        """A copy of the paths with every turtle's icon on top, as the window shows it."""
        image = self.path.copy()
        painter = QPainter(image)
        painter.setRenderHint(QPainter.SmoothPixmapTransform)
        for turtle in turtles:
            icon = self.icons.image(turtle.icon)
            painter.save()
            painter.translate(to_pixel(turtle.x, turtle.y))
            painter.rotate(-math.degrees(turtle.theta))
            painter.drawImage(QPointF(-icon.width() / 2.0, -icon.height() / 2.0), icon)
            painter.restore()
        painter.end()
        return image


def rgb888_bytes(image: QImage) -> bytes:
    """The image as tightly packed rows of RGB bytes (sensor_msgs/Image `rgb8`)."""
    rgb = image.convertToFormat(QImage.Format_RGB888)
    width, height = rgb.width(), rgb.height()
    bits = rgb.constBits()
    bits.setsize(rgb.sizeInBytes())
    raw = bytes(bits)
    stride = rgb.bytesPerLine()
    if stride == width * 3:
        return raw
    return b"".join(raw[row * stride: row * stride + width * 3] for row in range(height))
