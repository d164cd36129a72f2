"""What each key asks the robot to do, and when a velocity command is due.

Two publishing modes, both allowed by the text (UPMC part 1, #2.1.10):
- "on_key": one command per key press (turtlesim stops the turtle 1 s later);
- "continuous": the last command is repeated at a fixed rate until 's' sends zero.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from course_keyboard.drive import arrow_velocity
from mybot_teleop_core.keys import QUIT, STOP

ON_KEY, CONTINUOUS = "on_key", "continuous"
MODES = (ON_KEY, CONTINUOUS)


@dataclass(frozen=True)
class Velocity:
    linear: float = 0.0
    angular: float = 0.0


class TeleopCommands:
    """Maps keys to velocities scaled by linear_scale/angular_scale, and decides what to publish."""

    def __init__(self, linear_scale: float, angular_scale: float, mode: str = ON_KEY) -> None:
        if mode not in MODES:
            raise ValueError("publish_mode must be one of %s, got %r" % (", ".join(MODES), mode))
        self.linear_scale = float(linear_scale)
        self.angular_scale = float(angular_scale)
        self.mode = mode
        self.current = Velocity()
        self.quit = False

    def velocity_for(self, key: str) -> Optional[Velocity]:
        """The velocity a key asks for, or None for keys that are not motion keys."""
        if key == STOP:
            return Velocity()
        arrow = arrow_velocity(key, self.linear_scale, self.angular_scale)
        return None if arrow is None else Velocity(*arrow)

    def on_key(self, key: str) -> Optional[Velocity]:
        """Handle a key press; returns the velocity to publish now, if any."""
        if key == QUIT:
            self.quit = True
            return Velocity()  # leave the robot standing still
        velocity = self.velocity_for(key)
        if velocity is not None:
            self.current = velocity
        return velocity

    def on_tick(self) -> Optional[Velocity]:
        """Called at the node's rate: in continuous mode, repeat the current command."""
        return self.current if self.mode == CONTINUOUS else None
