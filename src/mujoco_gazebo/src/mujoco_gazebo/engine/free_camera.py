"""The free camera: gzclient's user camera, which the user orbits around a look-at point and
zooms. No ROS here: `OrbitView` is the view (what a client sets), `checked_view` turns wild
requests into a view or a clear error, `eye_pose` is the orbit's geometry, and `FreeCamera`
renders it with the sensor cameras' renderer (capture under the world's lock, draw outside).

Conventions (gazebo_msgs/OrbitView): world frame, radians, metres. `azimuth` is the direction
from the target to the eye in the xy plane, counter-clockwise from +x; `elevation` is the eye's
angle above the target's horizontal plane (positive looks down on the target). MuJoCo's own
MjvCamera measures both as the direction the eye *looks*; `apply_to` converts."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import mujoco
import numpy as np

from .camera import CameraConfig, OffscreenRenderer
from .limits import WORLD_BOUND_M

MAX_ELEVATION = math.radians(89.0)  # straight up or down has no defined "up" for the picture
MIN_DISTANCE = 0.05                  # m: closer than the near clip plane shows nothing useful
MAX_DISTANCE = 500.0                 # m: the far clip plane (FREE_CAMERA_CONFIG.far) is 1 km


class ViewError(ValueError):
    """A view that cannot be clamped into a valid one (a NaN or an infinity in it)."""


@dataclass(frozen=True)
class OrbitView:
    target: Tuple[float, float, float]
    azimuth: float
    elevation: float
    distance: float


# gzclient's default user camera: eye at (5, -5, 2) looking at the origin.
DEFAULT_VIEW = OrbitView(target=(0.0, 0.0, 0.0), azimuth=math.atan2(-5.0, 5.0),
                         elevation=math.atan2(2.0, math.hypot(5.0, 5.0)), distance=math.sqrt(54.0))

# gzclient's user camera has a 60 degree horizontal field of view.
FREE_CAMERA_CONFIG = CameraConfig(width=480, height=360, horizontal_fov=math.radians(60.0), near=0.02, far=1000.0)


def _clamp(value: float, low: float, high: float) -> float:
    return min(high, max(low, value))


def checked_view(target: Sequence[float], azimuth: float, elevation: float, distance: float) -> OrbitView:
    """A valid view from a request: ViewError if any value is NaN or infinite (or not a number);
    finite values beyond the limits are clamped (target within the world's +-10 km, elevation
    within +-89 degrees, distance within [MIN_DISTANCE, MAX_DISTANCE]); azimuth is wrapped to
    [-pi, pi]."""
    try:
        values = [float(v) for v in target] + [float(azimuth), float(elevation), float(distance)]
    except (TypeError, ValueError) as exc:
        raise ViewError("view values must be numbers: %s" % exc) from None
    if len(values) != 6:
        raise ViewError("target must have 3 coordinates, got %d" % (len(values) - 3))
    names = ("target.x", "target.y", "target.z", "azimuth", "elevation", "distance")
    bad = ["%s=%r" % (n, v) for n, v in zip(names, values) if not math.isfinite(v)]
    if bad:
        raise ViewError("view values must be finite: %s" % ", ".join(bad))
    x, y, z, az, el, dist = values
    return OrbitView(target=tuple(_clamp(c, -WORLD_BOUND_M, WORLD_BOUND_M) for c in (x, y, z)),
                     azimuth=math.remainder(az, 2.0 * math.pi),
                     elevation=_clamp(el, -MAX_ELEVATION, MAX_ELEVATION),
                     distance=_clamp(dist, MIN_DISTANCE, MAX_DISTANCE))


def eye_pose(view: OrbitView) -> Tuple[np.ndarray, np.ndarray]:
    """The eye's position and rotation (columns: forward, left, up) for a valid view."""
    ca, sa = math.cos(view.azimuth), math.sin(view.azimuth)
    ce, se = math.cos(view.elevation), math.sin(view.elevation)
    outward = np.array([ce * ca, ce * sa, se])        # from the target to the eye
    position = np.asarray(view.target, dtype=float) + view.distance * outward
    forward = -outward
    left = np.array([sa, -ca, 0.0])                     # horizontal: the picture is never rolled
    up = np.cross(forward, left)
    return position, np.column_stack([forward, left, up])


def apply_to(view: OrbitView, camera: mujoco.MjvCamera) -> None:
    """Set a MuJoCo free camera (e.g. the viewer window's) to the same view."""
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    camera.lookat[:] = view.target
    camera.distance = view.distance
    camera.azimuth = math.degrees(math.remainder(view.azimuth + math.pi, 2.0 * math.pi))
    camera.elevation = -math.degrees(view.elevation)


STILL_M = 1e-6  # a body that moved less than a micrometre (or rotated < 1e-6 rad) looks the same


class FreeCamera:
    """Renders the world from an OrbitView. `view` may be replaced from any thread (it is an
    immutable value); capture and draw run in one thread, as OffscreenRenderer requires.
    A still world seen from an unchanged view is not drawn again: `draw` returns the last
    picture (a settled robot in a browser tab then costs almost nothing); `drawn` counts the
    pictures really rendered."""

    def __init__(self, config: CameraConfig = FREE_CAMERA_CONFIG, view: OrbitView = DEFAULT_VIEW) -> None:
        self.config = config
        self.view = view
        self.renderer = OffscreenRenderer(config)
        self.drawn = 0
        self._captured: Optional[Tuple[mujoco.MjModel, np.ndarray, np.ndarray]] = None
        self._last: Optional[Tuple[OrbitView, Tuple[mujoco.MjModel, np.ndarray, np.ndarray], np.ndarray]] = None

    def prepare(self, model: mujoco.MjModel) -> None:
        """Outside the lock: open GL and upload `model`'s meshes and textures (slow, once per model)."""
        self.renderer.prepare(model)

    def capture(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        """Under the world's lock: copy the current poses (the cheap half)."""
        self.renderer.capture(model, data)
        self._captured = (model, data.xpos.copy(), data.xmat.copy())

    def _unchanged(self, view: OrbitView) -> bool:
        if self._last is None or self._captured is None or self._last[0] != view:
            return False
        (model, xpos, xmat), (last_model, last_xpos, last_xmat) = self._captured, self._last[1]
        return (model is last_model and xpos.shape == last_xpos.shape
                and float(np.abs(xpos - last_xpos).max(initial=0.0)) < STILL_M
                and float(np.abs(xmat - last_xmat).max(initial=0.0)) < STILL_M)

    def draw(self) -> np.ndarray:
        """Outside the lock: the captured scene from the current view, (height, width, 3) uint8."""
        view = self.view
        if self._unchanged(view):
            return self._last[2]
        position, rotation = eye_pose(view)
        pixels = self.renderer.draw(position, rotation)
        self.drawn += 1
        self._last = (view, self._captured, pixels)
        return pixels

    def close(self) -> None:
        self.renderer.close()
