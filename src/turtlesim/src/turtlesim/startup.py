"""A fast start for turtlesim_node: rospy without the waits and imports turtlesim does not need.

From launch to a callable /spawn, rospy's own start-up dominates (bench/turtlesim_bench.py).
Three parts of it do nothing for turtlesim; this module skips them without changing what
the node does:

- genpy imports numpy (~35 ms) only so that its error diagnosis (`check_type`, run after a
  failed serialisation) accepts numpy scalars. turtlesim never puts numpy values in a
  message, so genpy is imported with numpy hidden, and numpy stays unloaded.
- rospy imports roslib, whose package search imports catkin's find_in_workspaces, which
  loads catkin_pkg and pyparsing (~20 ms) for a function turtlesim never calls. roslib gets
  a stand-in that imports the real module at its first call.
- `rospy.init_node` polls for its registration with the master every 0.1 s, so it never
  returns in less than 0.1 s. During init_node the poll starts at 1 ms and backs off to
  rospy's own interval: the node goes on as soon as it is registered.
- `rospy.init_node` looks for python_logging.conf by crawling every package on
  ROS_PACKAGE_PATH, even when $ROS_HOME/config or ROS_ETC_DIR holds the file (which then
  wins anyway). The same file is found here without the crawl and named to rospy through
  ROS_PYTHON_LOG_CONFIG_FILE for the duration of the call.
"""
from __future__ import annotations

import importlib
import os
import sys
import time
import types
from contextlib import contextmanager
from typing import Callable, Iterator, List, Optional, Sequence

FIRST_POLL_S = 0.001
"""The first wait for the master registration; each further wait doubles, up to rospy's."""

LOG_CONFIG_ENV = "ROS_PYTHON_LOG_CONFIG_FILE"
LOG_CONFIG_NAMES = ("python_logging.conf", "python_logging.yaml")


@contextmanager
def hidden_module(name: str) -> Iterator[None]:
    """Imports of `name` fail inside the block (unless it is loaded already); nothing changes after."""
    if name in sys.modules:
        yield
        return
    sys.modules[name] = None  # type: ignore[assignment]  # makes `import name` raise ImportError
    try:
        yield
    finally:
        if sys.modules.get(name, "") is None:
            del sys.modules[name]


@contextmanager
def deferred_module(name: str, functions: Sequence[str]) -> Iterator[None]:
    """Inside the block, `import name` gives a stand-in whose `functions` import the real module
    at their first call; after the block, imports of `name` get the real module as usual."""
    if name in sys.modules:
        yield
        return
    stand_in = types.ModuleType(name, "stand-in for %s until one of its functions is called" % name)
    for function in functions:
        setattr(stand_in, function, _forwarder(stand_in, function))
    sys.modules[name] = stand_in
    try:
        yield
    finally:
        if sys.modules.get(name) is stand_in:
            del sys.modules[name]


def _forwarder(stand_in: types.ModuleType, function: str) -> Callable:
    def forward(*args, **kwargs):
        if sys.modules.get(stand_in.__name__) is stand_in:
            del sys.modules[stand_in.__name__]
        return getattr(importlib.import_module(stand_in.__name__), function)(*args, **kwargs)
    forward.__name__ = function
    return forward


def import_rospy():
    """rospy, with genpy loaded without numpy and roslib without catkin_pkg (see the module docstring)."""
    with hidden_module("numpy"):
        import genpy.message  # noqa: F401  (the module that would import numpy)
    with deferred_module("catkin.find_in_workspaces", ["find_in_workspaces"]):
        import rospy
    return rospy


class BackoffSleep:
    """Stands in for the `time` module in rospy.impl.init: its sleeps start short and double."""

    def __init__(self, real=time, first: float = FIRST_POLL_S) -> None:
        self._real = real
        self._next = first

    def sleep(self, seconds: float) -> None:
        wait = min(seconds, self._next)
        self._next = min(self._next * 2, max(seconds, self._next))
        self._real.sleep(wait)

    def __getattr__(self, name: str):
        return getattr(self._real, name)


@contextmanager
def quick_registration_poll() -> Iterator[None]:
    """rospy.impl.init's registration poll backs off from 1 ms instead of waiting 0.1 s each time."""
    import rospy.impl.init as rospy_init
    real = getattr(rospy_init, "time", None)
    if real is not time:  # not the rospy this was written for: leave it as it is
        yield
        return
    rospy_init.time = BackoffSleep(real)
    try:
        yield
    finally:
        rospy_init.time = real


def log_config_dirs(environ=os.environ) -> List[str]:
    """The folders rosgraph searches for python_logging.* before it crawls for its package."""
    import rospkg
    return [os.path.join(rospkg.get_ros_home(env=environ), "config"), rospkg.get_etc_ros_dir(env=environ)]


def log_config_file(environ=os.environ) -> Optional[str]:
    """The logging config rosgraph would pick, when it is found without a package crawl; else None."""
    if environ.get(LOG_CONFIG_ENV):
        return None  # rosgraph takes the variable as it is
    for folder in log_config_dirs(environ):
        for name in LOG_CONFIG_NAMES:
            path = os.path.join(folder, name)
            if os.path.isfile(path):
                return path
    return None


@contextmanager
def env_var(name: str, value: Optional[str]) -> Iterator[None]:
    """os.environ[name] = value inside the block (no change when value is None), restored after."""
    if value is None:
        yield
        return
    before = os.environ.get(name)
    os.environ[name] = value
    try:
        yield
    finally:
        if before is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = before


def init_node(name: str, argv: List[str]) -> None:
    """rospy.init_node(name, argv=argv), without the fixed 0.1 s wait and the package crawl, and
    with an exit that does not spin a core (course_rospy.quick_exit), and a TCPROS server that an
    idle or half-sent connection cannot block or exhaust (course_rospy.inbound_headers)."""
    rospy = import_rospy()
    from course_rospy import inbound_headers, quick_exit
    quick_exit.install()
    inbound_headers.install()
    with quick_registration_poll(), env_var(LOG_CONFIG_ENV, log_config_file()):
        rospy.init_node(name, argv=argv)
