"""The turtle world: which turtles exist, how they are named, spawned, killed and reset.

TurtleFrame knows nothing of ROS; the node turns its errors into failed service calls.
"""
from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Callable, Dict, List, Optional, Tuple

from turtlesim.canvas import RGB, Canvas
from turtlesim.constants import CENTRE
from turtlesim.names import name_error
from turtlesim.turtle import StepResult, Turtle


class TurtleError(Exception):
    """A request the world refuses (duplicate, unknown or invalid name, bad numbers)."""


@dataclass
class TurtleUpdate:
    """One turtle after one tick: what the node publishes for it."""

    name: str
    turtle: Turtle
    result: StepResult
    colour: Optional[RGB]
    """What its colour sensor reads, or None when it was not read (nobody listens)."""
    error: Optional[Exception] = None
    """Why this turtle's step failed (it was stopped and left where it was), or None."""


class TurtleFrame:
    """All turtles and the canvas they share."""

    def __init__(self, canvas: Canvas, rng: Optional[random.Random] = None,
                 canonical: Callable[[str], str] = str) -> None:
        """`canonical` maps a name to the namespace it gives the turtle's topics (the node passes
        rospy.resolve_name): two spellings of one namespace, like `turtle1` and `/turtle1`,
        cannot both be turtles."""
        self.canvas = canvas
        self.turtles: Dict[str, Turtle] = {}
        self._id_counter = 0
        self._rng = rng or random.Random()
        self._canonical = canonical

    def has(self, name: str) -> bool:
        return name in self.turtles

    def spawn(self, name: str, x: float, y: float, theta: float) -> str:
        """Add a turtle and return its name; an empty name picks the next free `turtleN`."""
        if not name:
            while True:
                self._id_counter += 1
                name = "turtle%d" % self._id_counter
                if self._owner(name) is None:
                    break
        elif name in self.turtles:
            raise TurtleError("A turtled named [%s] already exists" % name)
        else:
            problem = name_error(name)
            if problem:
                raise TurtleError(problem)
            owner = self._owner(name)
            if owner is not None:
                raise TurtleError("A turtled named [%s] already exists (as [%s])" % (name, owner))
        try:
            turtle = Turtle(x, y, theta, icon=self._rng.randrange(len(self.canvas.icons)))
        except ValueError as err:
            raise TurtleError(str(err)) from None
        self.turtles[name] = turtle
        return name

    def _owner(self, name: str) -> Optional[str]:
        """The existing turtle whose topics `name` would share, or None."""
        key = self._canonical(name)
        return next((n for n in self.turtles if self._canonical(n) == key), None)

    def kill(self, name: str) -> None:
        if name not in self.turtles:
            raise TurtleError("Tried to kill turtle [%s], which does not exist" % name)
        del self.turtles[name]

    def clear(self, background: RGB) -> None:
        self.canvas.fill(background)

    def reset(self, background: RGB) -> Tuple[List[str], str]:
        """Remove every turtle, spawn turtle1 at the centre, clear. Returns (removed, new name)."""
        removed = list(self.turtles)
        self.turtles.clear()
        self._id_counter = 0
        first = self.spawn("", CENTRE, CENTRE, 0.0)
        self.clear(background)
        return removed, first

    def update(self, dt: float, now: float, sense: Callable[[str], bool] = lambda name: True) -> List[TurtleUpdate]:
        """Advance every turtle one tick, draw their paths, read the colour sensors of the turtles
        `sense` names (the node: those someone listens to).

        A turtle whose step fails is stopped where it was and the error reported in its update;
        the others move on.
        """
        updates = [self._step(name, t, dt, now) for name, t in self.turtles.items()]
        self.canvas.draw((u.turtle.pen, u.result.segments) for u in updates)
        for u in updates:
            if sense(u.name):
                u.colour = self.canvas.colour_at(u.turtle.x, u.turtle.y)
        return updates

    @staticmethod
    def _step(name: str, turtle: Turtle, dt: float, now: float) -> TurtleUpdate:
        before = (turtle.x, turtle.y, turtle.theta)
        try:
            return TurtleUpdate(name, turtle, turtle.step(dt, now), None)
        except Exception as err:  # noqa: BLE001  (a bug in one turtle must not stop the others)
            turtle.x, turtle.y, turtle.theta = before
            turtle.stop()
            return TurtleUpdate(name, turtle, StepResult(), None, err)

    def render(self):
        return self.canvas.render(self.turtles.values())
