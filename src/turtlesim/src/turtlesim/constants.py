"""The numbers that define turtlesim, in one place (values of upstream Noetic turtlesim)."""
import math

CANVAS_PX = 500
"""The canvas is CANVAS_PX x CANVAS_PX pixels."""

METER_PX = 45
"""Pixels per metre: upstream uses the height of the turtle image."""

WORLD_SIZE = (CANVAS_PX - 1) / METER_PX
"""Width and height of the world in metres (11.088889)."""

CENTRE = WORLD_SIZE / 2.0
"""Where turtle1 starts, on both axes."""

TICK = 0.016
"""Simulation period in seconds (62.5 Hz); every update integrates exactly this dt."""

COMMAND_TIMEOUT = 1.0
"""A velocity command older than this (wall-clock seconds) stops the turtle."""

DEFAULT_PEN_RGB = (179, 184, 255)
DEFAULT_PEN_WIDTH = 3
DEFAULT_BACKGROUND_RGB = (69, 86, 255)
BACKGROUND_PARAMS = ("background_r", "background_g", "background_b")

TWO_PI = 2.0 * math.pi

FLOAT32_MAX = 3.4028234663852886e38
"""The largest float32: turtlesim/Pose carries float32, so no reported speed may exceed it."""

MAX_REACH = 1.0e6
"""How far (metres) from the canvas a teleport may carry a turtle within one tick; a farther
target is pulled back along the same line (the drawn path keeps its direction) before the
wall clamp. It keeps every coordinate finite whatever finite numbers a teleport carries."""

WALL_WARNING = "Oh no! I hit the wall! (Clamping from [x=%f, y=%f])"

TELEOP_SCALE_LINEAR = 2.0
TELEOP_SCALE_ANGULAR = 2.0
