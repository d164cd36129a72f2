"""The simulator window on a desktop (gzclient's place): MuJoCo's own viewer in passive mode,
showing the world's model and data, synced by the stepping loop. No ROS here; the server
decides when to open it and logs why it could not.

It needs a display (DISPLAY or WAYLAND_DISPLAY) and GLFW with a desktop OpenGL (GLX through
Mesa: Debian's libglx-mesa0 and libgl1-mesa-dri; the glfw wheel bundles libglfw). It opens on
gzclient's default view (free_camera.DEFAULT_VIEW) with MuJoCo's side panels hidden (Tab and
Shift+Tab show them). The mouse orbits, pans and zooms; a double click selects a body and
Ctrl+right drag pushes it. Closing the window leaves the simulation running, as closing
gzclient does."""
from __future__ import annotations

import math
import threading
from typing import List, Mapping

import mujoco

from .free_camera import DEFAULT_VIEW, OrbitView, apply_to, checked_view


class WindowUnavailable(RuntimeError):
    """The window cannot open here; the message says why."""


def display_problem(environ: Mapping[str, str]) -> str:
    """'' when a display is named in the environment, else why there is none."""
    if environ.get("DISPLAY") or environ.get("WAYLAND_DISPLAY"):
        return ""
    return "no display (DISPLAY and WAYLAND_DISPLAY are unset)"


def view_of(camera: mujoco.MjvCamera) -> OrbitView:
    """The OrbitView a MuJoCo free camera shows (apply_to's inverse)."""
    return checked_view(tuple(camera.lookat), math.radians(camera.azimuth) - math.pi,
                        -math.radians(camera.elevation), camera.distance)


class SimulatorWindow:
    """One viewer window at a time; `reopen` replaces it for a recompiled model (spawn, delete)
    and keeps the user's view."""

    def __init__(self, view: OrbitView = DEFAULT_VIEW) -> None:
        self._handle = None
        self._threads: List[threading.Thread] = []
        self._view = view

    @property
    def is_open(self) -> bool:
        return self._handle is not None and self._handle.is_running()

    def open(self, model: mujoco.MjModel, data: mujoco.MjData, environ: Mapping[str, str]) -> None:
        """Open the window on `model`/`data`; WindowUnavailable (with the reason) otherwise."""
        problem = display_problem(environ)
        if problem:
            raise WindowUnavailable(problem)
        before = set(threading.enumerate())
        try:
            import mujoco.viewer
            handle = mujoco.viewer.launch_passive(model, data, show_left_ui=False, show_right_ui=False)
        except Exception as exc:  # no GLFW, no GLX, display refused
            raise WindowUnavailable("%s: %s" % (type(exc).__name__, exc)) from None
        # the viewer's own thread: joined on close, or GLFW's exit hook frees what it still draws with
        self._threads = [t for t in threading.enumerate() if t not in before]
        with handle.lock():
            apply_to(self._view, handle.cam)
        self._handle = handle

    def sync(self) -> None:
        """Show the current state (and apply the user's mouse perturbations); the caller holds
        the world's lock. Nothing once the user closed the window."""
        if self.is_open:
            self._handle.sync()

    def reopen(self, model: mujoco.MjModel, data: mujoco.MjData, environ: Mapping[str, str]) -> None:
        """The same window for a new model (MuJoCo's passive viewer cannot swap models)."""
        if self._handle is None:
            return
        if not self._handle.is_running():
            self._handle = None  # closed by the user: stays closed
            return
        self._view = self._current_view()
        self.close()
        self.open(model, data, environ)

    def _current_view(self) -> OrbitView:
        try:
            with self._handle.lock():
                return view_of(self._handle.cam)
        except ValueError:
            return self._view

    def close(self, timeout: float = 5.0) -> None:
        """Close the window and wait for the viewer's thread to end."""
        handle, self._handle = self._handle, None
        if handle is not None:
            handle.close()
        threads, self._threads = self._threads, []
        for thread in threads:
            thread.join(timeout)
