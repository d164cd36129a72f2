"""The pen a turtle draws its path with, and what `set_pen` does to it."""
from __future__ import annotations

from dataclasses import dataclass, replace

from turtlesim.constants import DEFAULT_PEN_RGB, DEFAULT_PEN_WIDTH


@dataclass(frozen=True)
class Pen:
    """Colour, width and whether the pen touches the canvas."""

    r: int = DEFAULT_PEN_RGB[0]
    g: int = DEFAULT_PEN_RGB[1]
    b: int = DEFAULT_PEN_RGB[2]
    width: int = DEFAULT_PEN_WIDTH
    on: bool = True

    def set(self, r: int, g: int, b: int, width: int, off: int) -> "Pen":
        """The pen after a `set_pen` request.

        `off` lifts the pen and changes nothing else; otherwise the pen goes down
        with the new colour, and the width changes only when `width` is non-zero.
        Every number is held within 0..255, the range of set_pen's uint8 fields.
        """
        if off:
            return replace(self, on=False)
        r, g, b, width = (min(max(int(v), 0), 255) for v in (r, g, b, width))
        return Pen(r, g, b, width if width else self.width, True)

    @property
    def rgb(self) -> tuple:
        return (self.r, self.g, self.b)
