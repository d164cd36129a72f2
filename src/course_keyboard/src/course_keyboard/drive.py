"""What the arrow keys ask a mobile robot to do: turtle_teleop_key's map, shared by every course teleop.

Up drives forward, down backward, left turns counter-clockwise (angular.z > 0), right clockwise;
the node scales the unit command by its linear and angular speeds.
"""
from __future__ import annotations

from typing import Dict, Optional, Tuple

from course_keyboard.arrows import DOWN, LEFT, RIGHT, UP

ARROW_DRIVE: Dict[str, Tuple[float, float]] = {UP: (1.0, 0.0), DOWN: (-1.0, 0.0),
                                                LEFT: (0.0, 1.0), RIGHT: (0.0, -1.0)}


def arrow_velocity(key: str, linear_scale: float, angular_scale: float) -> Optional[Tuple[float, float]]:
    """(linear, angular) an arrow key asks for, scaled; None for every other key."""
    if key not in ARROW_DRIVE:
        return None
    linear, angular = ARROW_DRIVE[key]
    return linear_scale * linear, angular_scale * angular
