"""The canvas as drawing commands, for a page that draws it itself (the lab page, course_web).

Sending the rendered canvas costs a 500x500 render, a 750 kB image message and a JPEG encoding
per frame, at 30 frames a second, for a picture that changes by a few pixels a tick. A page
that holds the path image can instead be told what changed: which lines were drawn (pen colour
and width, canvas pixels), whether the canvas was cleared to a colour, and where each turtle is.

`SceneLog` collects that from the tick (`record`) and from clear/reset (`clear`), and hands it
out as numbered updates (`take`). `snapshot` is the whole state for a page that joins: the
path image (PNG), the turtle icons (PNG) and the number of the last update the path image
already holds, so that the page skips older updates and notices a gap (an update it missed:
it asks for a snapshot again). Plain Python and Qt images: the node publishes the updates as
JSON on `~scene` and answers `~canvas` with the snapshot.
"""
from __future__ import annotations

import base64
import json
import secrets
from typing import FrozenSet, Hashable, Iterable, List, Optional, Sequence, Tuple

from PyQt5.QtCore import QBuffer, QByteArray, QIODevice
from PyQt5.QtGui import QImage

from turtlesim.canvas import RGB
from turtlesim.constants import METER_PX, WORLD_SIZE
from turtlesim.pen import Pen
from turtlesim.turtle import Segment

PIXEL_DECIMALS = 1  # canvas pixels are sent with one decimal (lines are drawn at sub-pixel precision)
THETA_DECIMALS = 4


def png_base64(image: QImage) -> str:
    """The image as base64 PNG text (what a browser draws from a data URL or a Blob)."""
    data = QByteArray()
    buffer = QBuffer(data)
    buffer.open(QIODevice.WriteOnly)
    image.save(buffer, "PNG")
    buffer.close()
    return base64.b64encode(bytes(data)).decode("ascii")


def pixel(v: float, flip: bool) -> float:
    """A world coordinate (metres) as a canvas pixel coordinate; `flip` for y (down on the canvas)."""
    return round(((WORLD_SIZE - v) if flip else v) * METER_PX, PIXEL_DECIMALS)


class SceneLog:
    """What the canvas did since the last update handed out."""

    def __init__(self) -> None:
        self.run = secrets.token_hex(4)
        """Which process the numbers count for: a page that sees another run starts from a snapshot."""
        self.seq = 0
        """The number of the last update handed out (or skipped: nobody was listening)."""
        self._clear: Optional[RGB] = None
        self._strokes: List[list] = []
        self._turtles: List[list] = []
        self._sent_turtles: Optional[List[list]] = None

    def record(self, strokes: Iterable[Tuple[Pen, Sequence[Segment]]],
               turtles: Iterable[Tuple[str, float, float, float, int]]) -> None:
        """One tick: the lines each pen drew (pens that are up draw nothing), and every turtle
        as (name, x, y, theta, icon) in world units."""
        for pen, segments in strokes:
            if not pen.on:
                continue
            for (x0, y0), (x1, y1) in segments:
                self._strokes.append([pen.r, pen.g, pen.b, pen.width, pixel(x0, False), pixel(y0, True),
                                      pixel(x1, False), pixel(y1, True)])
        self._turtles = [[name, pixel(x, False), pixel(y, True), round(theta, THETA_DECIMALS), icon]
                         for name, x, y, theta, icon in turtles]

    def clear(self, background: RGB) -> None:
        """The canvas was wiped to `background`: lines drawn before it no longer matter."""
        self._clear = tuple(background)
        self._strokes = []

    def changed(self) -> bool:
        return self._clear is not None or bool(self._strokes) or self._turtles != self._sent_turtles

    def take(self) -> Optional[str]:
        """The next update as JSON, or None when nothing changed. Its fields: run, seq, clear (an
        [r, g, b] to fill with first, or null), strokes ([r, g, b, width, x0, y0, x1, y1] in
        canvas pixels, in drawing order), turtles ([name, x, y, theta, icon]; theta in radians,
        counter-clockwise as on the canvas)."""
        if not self.changed():
            return None
        self.seq += 1
        update = {"run": self.run, "seq": self.seq, "clear": list(self._clear) if self._clear is not None else None,
                  "strokes": self._strokes, "turtles": self._turtles}
        self._clear, self._strokes, self._sent_turtles = None, [], self._turtles
        return json.dumps(update, separators=(",", ":"))

    def state(self) -> Tuple[str, int, List[list]]:
        """(run, seq, turtles) now: what a snapshot taken now holds besides the path image."""
        return self.run, self.seq, list(self._turtles)


def snapshot_json(state: Tuple[str, int, List[list]], paths: QImage, icons: Sequence[QImage]) -> str:
    """The whole canvas as JSON: run, seq (the last update `paths` holds: lines still pending are drawn
    on it already, and drawing them again from the next update leaves the same pixels), width,
    height, paths (PNG, base64), icons (PNG, base64, by index), turtles (as in SceneLog.take)."""
    run, seq, turtles = state
    return json.dumps({"run": run, "seq": seq, "width": paths.width(), "height": paths.height(),
                       "paths": png_base64(paths), "icons": [png_base64(i) for i in icons],
                       "turtles": turtles}, separators=(",", ":"))


class FrameGate:
    """Whether the ~image thread renders a frame now: only for a subscriber, and only when the
    canvas changed since the last frame or a subscriber came (it needs a first frame)."""

    def __init__(self) -> None:
        self.renders = 0
        self._seen: Optional[Tuple[FrozenSet[Hashable], int]] = None

    def due(self, subscribers: FrozenSet[Hashable], changes: int) -> bool:
        """`subscribers`: who is connected now (any identity per connection); `changes`: a count
        of what changed the picture."""
        if not subscribers:
            self._seen = None
            return False
        if self._seen == (subscribers, changes):
            return False
        self._seen = (subscribers, changes)
        self.renders += 1
        return True
