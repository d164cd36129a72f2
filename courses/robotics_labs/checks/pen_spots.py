"""Where the `color` milestone (001 2.2 Part B) drives the turtle, and how it reads the pen colour.

The text asks for a red line "when approaching the screen corners" (#2.2.7, Figure 2) with
set_pen calls "only when entering or leaving the corners", and gives no corner size. So the
turtle circles deep in each corner, where any student's threshold counts it as in the corner,
and in the middle of the canvas, where none does; the colour under the turtle (turtlesim's
color_sensor, the pixel its pen just drew) is the pen's colour.
"""
from __future__ import annotations

from typing import NamedTuple, Sequence, Tuple

from turtlesim.constants import CENTRE, WORLD_SIZE

CORNER_DEPTH = 0.5     # m from both walls: the centre of the circle driven in a corner
CIRCLE_RADIUS = 0.2    # m: the circle stays between 0.3 and 0.7 m from the walls
CIRCLE_SPEED = 1.0     # m/s along the circle
Rgb = Tuple[int, int, int]


class Spot(NamedTuple):
    """A place the turtle circles around, and whether the pen must be red there."""

    name: str
    x: float
    y: float
    corner: bool

    def start(self, radius: float = CIRCLE_RADIUS) -> Tuple[float, float, float]:
        """Teleport target (x, y, theta): on the circle, heading so that a left turn circles the spot."""
        return self.x, self.y - radius, 0.0


def corners(depth: float = CORNER_DEPTH, size: float = WORLD_SIZE) -> Tuple[Spot, ...]:
    far = size - depth
    return (Spot("bottom-left", depth, depth, True), Spot("bottom-right", far, depth, True),
            Spot("top-right", far, far, True), Spot("top-left", depth, far, True))


MIDDLE = Spot("middle", CENTRE, CENTRE, False)


def tour(depth: float = CORNER_DEPTH) -> Tuple[Spot, ...]:
    """Each corner, entered from the middle and left back to it."""
    return tuple(spot for corner in corners(depth) for spot in (corner, MIDDLE))


def circle_command(radius: float = CIRCLE_RADIUS, speed: float = CIRCLE_SPEED) -> Tuple[float, float]:
    """(linear.x, angular.z) that drives a counter-clockwise circle of `radius`."""
    return speed, speed / radius


def is_red(rgb: Rgb) -> bool:
    """Red as a student would pick it: a strong red channel, green and blue at most half of it
    ((255, 0, 0) in the text; the default pen (179, 184, 255) and background are not red)."""
    r, g, b = rgb
    return r >= 128 and 2 * g <= r and 2 * b <= r


def settled(colours: Sequence[Rgb], want_red: bool, count: int = 5) -> bool:
    """The last `count` colours are all red (or all not red)."""
    return len(colours) >= count and all(is_red(c) == want_red for c in colours[-count:])
