"""The small base every robot plugin stands on, and the registry from a URDF's
<plugin filename="libgazebo_ros_*.so"> to the class that simulates it.

A plugin is the ROS face of one Gazebo plugin: it is built when its model is spawned (it
advertises and subscribes then), `update` runs with the world lock held at the plugin's own
rate in simulated time, `reset` follows reset_world/reset_simulation, `close` follows the
model's deletion. Plugins ask the World for what they need by model, joint and link name;
MuJoCo's ids and arrays stay inside the World."""
from __future__ import annotations

import threading
from typing import Callable, Dict, List, Type

import rospy

from ..engine.world import ModelEntry, World


def ns_join(ns: str, name: str) -> str:
    """`name` resolved in namespace `ns` (absolute names stay as they are)."""
    if name.startswith("/"):
        return name
    ns = ns.strip("/")
    return "/%s/%s" % (ns, name) if ns else "/" + name


def param_float(params: dict, key: str, default: float) -> float:
    """A numeric <plugin> parameter; `default` when it is missing or not a number."""
    try:
        return float(params.get(key, default))
    except ValueError:
        return default


class Plugin:
    """A period in simulated seconds and the bookkeeping to run at it; the ROS handles it
    registers in `_handles` are unregistered on close. A subclass is built as
    `cls(entry, spec, lock, world)`: its model, its <plugin> block, the world lock (its ROS
    callbacks take it before touching the world) and the world."""

    period = 0.0

    def __init__(self) -> None:
        self._next = 0.0
        self._handles: List = []

    def due(self, now: float) -> bool:
        if now + 1e-9 < self._next:
            return False
        self._next = now + self.period if now - self._next > self.period else self._next + self.period
        return True

    def update(self, world: World, now: float) -> None:
        raise NotImplementedError

    def reset(self, world: World) -> None:
        self._next = 0.0

    def close(self) -> None:
        for handle in self._handles:
            handle.unregister()
        self._handles = []


#: <plugin filename> -> the class that simulates it (filled by `register`)
REGISTRY: Dict[str, Type[Plugin]] = {}


def register(*filenames: str) -> Callable[[Type[Plugin]], Type[Plugin]]:
    """Class decorator: this class simulates the Gazebo plugins of these file names."""
    def add(cls: Type[Plugin]) -> Type[Plugin]:
        for filename in filenames:
            REGISTRY[filename] = cls
        return cls
    return add


def make_plugins(entry: ModelEntry, lock: threading.Lock, world: World) -> List[Plugin]:
    """Instantiate the plugins a model's URDF asks for; unknown ones are logged and skipped."""
    out: List[Plugin] = []
    for spec in entry.plugins:
        cls = REGISTRY.get(spec.filename)
        if cls is None:
            rospy.loginfo("%s: plugin %s (%s) not simulated" % (entry.name, spec.name, spec.filename))
            continue
        out.append(cls(entry, spec, lock, world))
    return out
