"""Headless rendering of pinhole cameras: `OffscreenRenderer` draws a scene from any eye
(capture under the world's lock, draw outside it), `BodyCamera` is one fixed to a MuJoCo body
as Gazebo's camera sensor (along the body's +x axis with +z up), and the free camera
(free_camera.py) orbits a point. No ROS here: they turn (model, data) into RGB arrays; the
ROS side publishes them.

OpenGL comes from a headless backend (EGL, else OSMesa; `MUJOCO_GL` picks the first to try,
`MUJOCO_GL=disable` turns rendering off). The GL context is made lazily, in the thread that
renders, and one context serves every recompiled model (only MuJoCo's MjrContext is rebuilt
when spawn/delete produce a new MjModel)."""
from __future__ import annotations

import atexit
import importlib
import math
import os
from dataclasses import dataclass
from typing import List, Optional, Tuple

import mujoco
import numpy as np

_DISABLED = ("disable", "disabled", "off", "false", "0")
_HEADLESS = ("egl", "osmesa")


class RenderUnavailable(RuntimeError):
    """No OpenGL backend could be opened; the message says what was tried and why it failed."""


@dataclass(frozen=True)
class CameraConfig:
    """Image size and optics (Gazebo's <camera>: horizontal_fov, image, clip)."""

    width: int = 320
    height: int = 240
    horizontal_fov: float = 1.3962634   # rad, the RRBot tutorial's value
    near: float = 0.02
    far: float = 300.0
    shadows: bool = False               # MuJoCo's shadow maps triple the render time on llvmpipe
    background: Tuple[int, int, int] = (178, 178, 178)  # Gazebo's default sky grey (0.7)

    def __post_init__(self) -> None:
        if self.width < 1 or self.height < 1:
            raise ValueError("camera image size must be positive, got %dx%d" % (self.width, self.height))
        if not 0.0 < self.horizontal_fov < math.pi:
            raise ValueError("horizontal_fov must be in (0, pi), got %r" % self.horizontal_fov)
        if not 0.0 < self.near < self.far:
            raise ValueError("clip planes need 0 < near < far, got %r, %r" % (self.near, self.far))

    @property
    def focal_length(self) -> float:
        """Focal length in pixels (square pixels), as gazebo_ros_camera computes it."""
        return self.width / (2.0 * math.tan(self.horizontal_fov / 2.0))

    @property
    def vertical_fov(self) -> float:
        return 2.0 * math.atan(self.height / (2.0 * self.focal_length))

    def intrinsics(self) -> Tuple[float, float, float, float]:
        """fx, fy, cx, cy of the ideal pinhole (gazebo_ros_camera's principal point convention)."""
        f = self.focal_length
        return f, f, (self.width + 1) / 2.0, (self.height + 1) / 2.0


def backend_order(requested: str) -> List[str]:
    """Headless GL backends to try, given MUJOCO_GL: [] when rendering is disabled."""
    requested = requested.lower().strip()
    if requested in _DISABLED:
        return []
    if requested in _HEADLESS:
        return [requested] + [b for b in _HEADLESS if b != requested]
    return list(_HEADLESS)


def open_gl_context(width: int, height: int, requested: Optional[str] = None) -> Tuple[object, str]:
    """A current, headless GL context and the backend's name; RenderUnavailable otherwise."""
    requested = os.environ.get("MUJOCO_GL", "") if requested is None else requested
    order = backend_order(requested)
    if not order:
        raise RenderUnavailable("rendering disabled (MUJOCO_GL=%s)" % requested)
    failures = []
    for backend in order:
        try:
            module = importlib.import_module("mujoco.%s" % backend)
            context = module.GLContext(width, height)
            context.make_current()
            return context, backend
        except Exception as exc:  # ImportError, EGL/OSMesa errors: try the next one
            failures.append("%s: %s" % (backend, str(exc).strip().splitlines()[0] if str(exc).strip()
                                        else type(exc).__name__))
    raise RenderUnavailable("no headless OpenGL backend (%s)" % "; ".join(failures))


class OffscreenRenderer:
    """Renders a MuJoCo scene from an eye placed by the caller. Two halves, so the world's lock
    is held only for the cheap one: `capture` copies the model's geoms into the scene (needs the
    model and data consistent), `draw` rasterises and reads the pixels (needs neither).
    Not thread-safe: one thread captures and draws."""

    def __init__(self, config: CameraConfig, max_geom: int = 2000) -> None:
        self.config = config
        self.max_geom = max_geom
        self.backend = ""
        self._gl = None
        self._failure: Optional[RenderUnavailable] = None
        self._model: Optional[mujoco.MjModel] = None
        self._scene: Optional[mujoco.MjvScene] = None
        self._context: Optional[mujoco.MjrContext] = None
        self._option = mujoco.MjvOption()
        self._free_camera = mujoco.MjvCamera()
        self._rect = mujoco.MjrRect(0, 0, config.width, config.height)
        self._pixels = np.empty((config.height, config.width, 3), dtype=np.uint8)
        self._depth = np.empty((config.height, config.width), dtype=np.float32)

    def prepare(self, model: mujoco.MjModel) -> None:
        """Open GL (once) and set up the scene for `model` (again only when the model changes)."""
        if self._failure is not None:
            raise self._failure
        if self._gl is None:
            try:
                self._gl, self.backend = open_gl_context(self.config.width, self.config.height)
            except RenderUnavailable as exc:
                self._failure = exc
                raise
            atexit.register(self.close)  # before the backend's own exit hook tears the display down
        self._gl.make_current()
        if model is self._model:
            return
        if self._context is not None:
            self._context.free()
        # the offscreen buffer is sized from the model's <visual><global offwidth/offheight>
        glob = model.vis.global_
        saved = (glob.offwidth, glob.offheight)
        glob.offwidth, glob.offheight = max(saved[0], self.config.width), max(saved[1], self.config.height)
        try:
            self._context = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_100)
        finally:
            glob.offwidth, glob.offheight = saved
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, self._context)
        self._scene = mujoco.MjvScene(model, maxgeom=self.max_geom)
        self._scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = self.config.shadows
        self._scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = False
        self._scene.flags[mujoco.mjtRndFlag.mjRND_HAZE] = False  # haze fades the horizon to black
        self._model = model

    def capture(self, model: mujoco.MjModel, data: mujoco.MjData, hidden_body: int = -1) -> None:
        """Copy the bodies' current poses into the scene (geoms of `hidden_body` invisible).
        Raises RenderUnavailable when no GL backend can be opened (and on every later call)."""
        if hidden_body >= model.nbody:
            raise ValueError("body id %d out of range [0, %d)" % (hidden_body, model.nbody))
        self.prepare(model)
        mujoco.mjv_defaultFreeCamera(model, self._free_camera)
        mujoco.mjv_updateScene(model, data, self._option, None, self._free_camera,
                               mujoco.mjtCatBit.mjCAT_ALL, self._scene)
        if hidden_body >= 0:
            self._hide_body(model, hidden_body)

    def draw(self, position: np.ndarray, rotation: np.ndarray) -> np.ndarray:
        """The last captured scene seen from an eye at `position` whose rotation's columns are
        forward, left and up: (height, width, 3) uint8, row 0 at the top."""
        if self._scene is None:
            raise RuntimeError("draw() before capture()")
        self._gl.make_current()
        self._place_camera(np.asarray(position, dtype=float), np.asarray(rotation, dtype=float))
        mujoco.mjr_render(self._rect, self._scene, self._context)
        mujoco.mjr_readPixels(self._pixels, self._depth, self._rect, self._context)
        self._pixels[self._depth >= 1.0] = self.config.background  # nothing hit: sky
        return np.flipud(self._pixels).copy()  # GL's rows start at the bottom

    def _place_camera(self, position: np.ndarray, rotation: np.ndarray) -> None:
        """Point the scene's GL eyes along the rotation's first column with its third one up."""
        forward, up = rotation[:, 0], rotation[:, 2]
        half_height = self.config.near * math.tan(self.config.vertical_fov / 2.0)
        for eye in self._scene.camera:
            eye.pos[:] = position
            eye.forward[:] = forward
            eye.up[:] = up
            eye.frustum_center = 0.0
            eye.frustum_width = 0.0   # 0: width from the viewport's aspect ratio
            eye.frustum_bottom, eye.frustum_top = -half_height, half_height
            eye.frustum_near, eye.frustum_far = self.config.near, self.config.far
            eye.orthographic = 0
        for i in range(self._scene.nlight):  # the headlight shines from the eye, as it looks
            light = self._scene.lights[i]
            if light.headlight:
                light.pos[:], light.dir[:] = position, forward

    def _hide_body(self, model: mujoco.MjModel, body_id: int) -> None:
        """Make a body invisible (a camera's housing: the eye sits inside it)."""
        for i in range(self._scene.ngeom):
            geom = self._scene.geoms[i]
            if geom.objtype == mujoco.mjtObj.mjOBJ_GEOM and model.geom_bodyid[geom.objid] == body_id:
                geom.rgba[3] = 0.0

    def close(self) -> None:
        """Free the GL resources; safe to call twice and from another thread."""
        context, gl = self._context, self._gl
        if gl is not None:
            atexit.unregister(self.close)
        self._context, self._gl, self._scene, self._model = None, None, None, None
        try:
            if gl is not None:
                gl.make_current()
            if context is not None:
                context.free()
        except Exception:
            pass  # the context may be current in the rendering thread: destroying it below frees all
        try:
            if gl is not None:
                gl.free()
        except Exception:
            pass


class BodyCamera(OffscreenRenderer):
    """A camera fixed to a body, as Gazebo's camera sensor: it looks along the body's +x axis
    with +z up, and does not see its own housing."""

    def render(self, model: mujoco.MjModel, data: mujoco.MjData, body_id: int) -> np.ndarray:
        """The camera's image, (height, width, 3) uint8, row 0 at the top. Raises
        RenderUnavailable when no GL backend can be opened (and on every later call)."""
        if not 0 <= body_id < model.nbody:
            raise ValueError("body id %d out of range [0, %d)" % (body_id, model.nbody))
        self.capture(model, data, hidden_body=body_id)
        return self.draw(data.xpos[body_id], data.xmat[body_id].reshape(3, 3))
