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

Each turtle is sent with its velocity, and the page moves it between updates as turtlesim would
(course_web's canvas_panel.js). So an update is needed soon only when the page could not have
foreseen it: a clear, a turtle that came or went, a velocity that changed, a pose off the course
its last velocity gave (a teleport, the wall). Those go out within FAST_TICKS ticks; a turtle that
only goes on as foreseen, every STEADY_TICKS (its lines arrive in chunks, under its icon). Each
update is a message through turtlesim, lab_view, JupyterLab's proxy and the browser: a turtle
driving in circles costs 7.8 of them a second instead of 20.8.
"""
from __future__ import annotations

import base64
import json
import secrets
from typing import Dict, FrozenSet, Hashable, Iterable, List, Optional, Sequence, Tuple

from PyQt5.QtCore import QBuffer, QByteArray, QIODevice
from PyQt5.QtGui import QImage

import math

from turtlesim.canvas import RGB
from turtlesim.constants import METER_PX, TICK, WORLD_SIZE
from turtlesim.pen import Pen
from turtlesim.turtle import Segment

PIXEL_DECIMALS = 1  # canvas pixels are sent with one decimal (lines are drawn at sub-pixel precision)
THETA_DECIMALS = 4
FAST_TICKS = 3  # what the page could not foresee goes out within 3 ticks (20.8 updates a second at most)
STEADY_TICKS = 8  # a turtle going on as foreseen: an update every 8 ticks (7.8 a second)
FORESEEN_PX = 0.5  # a pose within half a pixel of where its last velocity took it was foreseen

TurtleState = Tuple[str, float, float, float, int, float, float, float]
"""(name, x, y, theta, icon, vx, vy, w): world units, the velocity in the turtle's frame as it moves."""


def foreseen(x: float, y: float, theta: float, vx: float, vy: float, w: float) -> Tuple[float, float, float]:
    """Where one tick takes a turtle at (x, y, theta) with this velocity: turtle.Turtle.step's own
    integration (the heading first, then the move along it), without walls or teleports."""
    theta += w * TICK
    cos_t, sin_t = math.cos(theta), math.sin(theta)
    return x + (cos_t * vx - sin_t * vy) * TICK, y + (sin_t * vx + cos_t * vy) * TICK, theta


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
        self._foreseen: Dict[str, Tuple[float, ...]] = {}  # name -> (x, y, theta, vx, vy, w) the page expects now
        self._surprise = False  # something the page cannot foresee happened since the last update
        self._ticks = 0  # ticks recorded since the last update handed out
        self._raw: List[TurtleState] = []  # the last tick's turtles, unrounded

    def record(self, strokes: Iterable[Tuple[Pen, Sequence[Segment]]], turtles: Iterable[TurtleState]) -> None:
        """One tick: the lines each pen drew (pens that are up draw nothing), and every turtle
        with its velocity (TurtleState)."""
        for pen, segments in strokes:
            if not pen.on:
                continue
            for (x0, y0), (x1, y1) in segments:
                self._strokes.append([pen.r, pen.g, pen.b, pen.width, pixel(x0, False), pixel(y0, True),
                                      pixel(x1, False), pixel(y1, True)])
        turtles = list(turtles)
        self._raw = turtles
        self._turtles = [[name, pixel(x, False), pixel(y, True), round(theta, THETA_DECIMALS), icon,
                          round(vx * METER_PX, PIXEL_DECIMALS), round(vy * METER_PX, PIXEL_DECIMALS),
                          round(w, THETA_DECIMALS)]
                         for name, x, y, theta, icon, vx, vy, w in turtles]
        self._ticks += 1
        if not self._surprise:
            self._surprise = not self._as_foreseen(turtles)
        self._foreseen = {name: foreseen(*state) + state[3:] for name, state in self._foreseen.items()}

    def _as_foreseen(self, turtles: List[TurtleState]) -> bool:
        """Whether every turtle is where the page, moving them from the last update, draws them."""
        if {t[0] for t in turtles} != set(self._foreseen):
            return False
        for name, x, y, theta, _icon, vx, vy, w in turtles:
            fx, fy, ftheta, fvx, fvy, fw = self._foreseen[name]
            if (vx, vy, w) != (fvx, fvy, fw):
                return False
            # the pose after this tick against the page's: foreseen() of the pose it last had
            px, py, ptheta = foreseen(fx, fy, ftheta, fvx, fvy, fw)
            if (math.hypot(px - x, py - y) * METER_PX > FORESEEN_PX
                    or abs(math.remainder(ptheta - theta, math.tau)) > FORESEEN_PX / METER_PX):
                return False
        return True

    def clear(self, background: RGB) -> None:
        """The canvas was wiped to `background`: lines drawn before it no longer matter."""
        self._clear = tuple(background)
        self._strokes = []

    def changed(self) -> bool:
        return self._clear is not None or bool(self._strokes) or self._turtles != self._sent_turtles

    def due(self) -> bool:
        """Whether an update should go out now: something the page cannot foresee, FAST_TICKS
        after the last one; anything else that changed, STEADY_TICKS after it."""
        if not self.changed():
            return False
        return self._ticks >= (FAST_TICKS if self._surprise or self._clear is not None else STEADY_TICKS)

    def take(self) -> Optional[str]:
        """The next update as JSON, or None when nothing changed. Its fields: run, seq, clear (an
        [r, g, b] to fill with first, or null), strokes ([r, g, b, width, x0, y0, x1, y1] in
        canvas pixels, in drawing order), turtles ([name, x, y, theta, icon, vx, vy, w]; theta in
        radians, counter-clockwise as on the canvas; vx, vy the velocity in the turtle's own frame
        in canvas pixels a second, forward and to its left; w in radians a second, counter-clockwise),
        from which the page moves them on until the next update."""
        if not self.changed():
            return None
        self.seq += 1
        update = {"run": self.run, "seq": self.seq, "clear": list(self._clear) if self._clear is not None else None,
                  "strokes": self._strokes, "turtles": self._turtles}
        self._clear, self._strokes, self._sent_turtles = None, [], self._turtles
        self._foreseen = {name: (x, y, theta, vx, vy, w) for name, x, y, theta, _icon, vx, vy, w in self._raw}
        self._surprise, self._ticks = False, 0
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
