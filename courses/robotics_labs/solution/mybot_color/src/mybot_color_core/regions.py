"""Where the turtle is on the turtlesim canvas: in a corner, near a side, and when that changes.

Only changes matter to the node: the text asks for as few set_pen calls as possible
(one on entering a corner, one on leaving it), and /clear is likewise called only
when the turtle moves to another side region.
"""
from __future__ import annotations

from typing import Optional, Tuple

WORLD_SIZE = 499.0 / 45.0  # upstream turtlesim: (500 - 1) px / 45 px per metre
ENTER, LEAVE = "enter", "leave"
LEFT, RIGHT, BOTTOM, TOP = "left", "right", "bottom", "top"

RED_PEN = (255, 0, 0, 3)
DEFAULT_PEN = (179, 184, 255, 3)
DEFAULT_BACKGROUND = (69, 86, 255)
SIDE_BACKGROUNDS = {LEFT: (0, 128, 0), RIGHT: (200, 120, 0), BOTTOM: (120, 0, 120), TOP: (0, 140, 140)}


def in_corner(x: float, y: float, margin: float, size: float = WORLD_SIZE) -> bool:
    """True within `margin` metres of two sides at once."""
    near_x = x < margin or x > size - margin
    near_y = y < margin or y > size - margin
    return near_x and near_y


def nearest_side(x: float, y: float, margin: float, size: float = WORLD_SIZE) -> Optional[str]:
    """The side the turtle is within `margin` of (the closest one), or None in the middle."""
    distances = {LEFT: x, RIGHT: size - x, BOTTOM: y, TOP: size - y}
    side, distance = min(distances.items(), key=lambda item: item[1])
    return side if distance < margin else None


class CornerWatcher:
    """Reports ENTER when the turtle enters a corner region and LEAVE when it leaves it."""

    def __init__(self, margin: float, size: float = WORLD_SIZE) -> None:
        self.margin, self.size = margin, size
        self.inside = False

    def update(self, x: float, y: float) -> Optional[str]:
        now = in_corner(x, y, self.margin, self.size)
        if now == self.inside:
            return None
        self.inside = now
        return ENTER if now else LEAVE


class SideWatcher:
    """Reports the new background colour when the turtle moves to another side region."""

    def __init__(self, margin: float, size: float = WORLD_SIZE) -> None:
        self.margin, self.size = margin, size
        self.side: Optional[str] = None

    def update(self, x: float, y: float) -> Optional[Tuple[int, int, int]]:
        side = nearest_side(x, y, self.margin, self.size)
        if side == self.side:
            return None
        self.side = side
        return SIDE_BACKGROUNDS[side] if side else DEFAULT_BACKGROUND
