"""The free camera without ROS: the orbit's geometry, wild requests (NaN, inf, huge: a clear
error or a clamp, never a crash), MuJoCo's MjvCamera seeing the same, and rendered pictures
(skipped, with the reason, only when no headless GL backend can be opened)."""
import math
from pathlib import Path

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mujoco_gazebo.engine import database
from mujoco_gazebo.engine.camera import CameraConfig, RenderUnavailable, open_gl_context
from mujoco_gazebo.engine.free_camera import (DEFAULT_VIEW, MAX_DISTANCE, MAX_ELEVATION, MIN_DISTANCE, FreeCamera,
                                              OrbitView, ViewError, apply_to, checked_view, eye_pose)
from mujoco_gazebo.engine.frames import Pose
from mujoco_gazebo.engine.limits import WORLD_BOUND_M
from mujoco_gazebo.engine.window import display_problem, view_of
from mujoco_gazebo.engine.world import World

from course_testkit.pictures import orange_pixels, red_pixels

RRBOT = (Path(__file__).resolve().parents[3] / "rrbot_description" / "urdf" / "rrbot.urdf").read_text()


def test_default_view_is_gzclients():
    position, rotation = eye_pose(DEFAULT_VIEW)
    assert position == pytest.approx([5.0, -5.0, 2.0])
    forward = rotation[:, 0]
    assert forward == pytest.approx(-position / np.linalg.norm(position))  # looks at the origin


@pytest.mark.parametrize("azimuth, elevation, expected", [
    (0.0, 0.0, (2.0, 0.0, 1.0)), (math.pi / 2, 0.0, (0.0, 2.0, 1.0)), (math.pi, 0.0, (-2.0, 0.0, 1.0)),
    (0.0, math.pi / 6, (2.0 * math.cos(math.pi / 6), 0.0, 1.0 + 1.0))])
def test_eye_orbits_the_target(azimuth, elevation, expected):
    view = checked_view((0.0, 0.0, 1.0), azimuth, elevation, 2.0)
    position, rotation = eye_pose(view)
    assert position == pytest.approx(expected)
    assert rotation.T @ rotation == pytest.approx(np.eye(3))  # orthonormal
    assert np.linalg.det(rotation) == pytest.approx(1.0)      # right-handed: forward, left, up
    assert rotation[2, 1] == pytest.approx(0.0)                # never rolled
    assert rotation[2, 2] > 0                                  # up is up


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize("field", range(6))
def test_non_finite_values_are_refused_by_name(field, bad):
    values = [0.0, 0.0, 0.0, 0.0, 0.3, 3.0]
    values[field] = bad
    with pytest.raises(ViewError, match="finite"):
        checked_view(values[:3], *values[3:])


def test_not_numbers_are_refused():
    with pytest.raises(ViewError):
        checked_view(("a", 0, 0), 0, 0, 1)
    with pytest.raises(ViewError):
        checked_view((0, 0), 0, 0, 1)


anything = st.floats(allow_nan=True, allow_infinity=True)


@settings(max_examples=300, deadline=None)
@given(st.tuples(anything, anything, anything), anything, anything, anything)
def test_any_request_gives_a_valid_view_or_a_view_error(target, azimuth, elevation, distance):
    try:
        view = checked_view(target, azimuth, elevation, distance)
    except ViewError:
        assert not all(math.isfinite(v) for v in (*target, azimuth, elevation, distance))
        return
    assert all(abs(c) <= WORLD_BOUND_M for c in view.target)
    assert -math.pi <= view.azimuth <= math.pi
    assert -MAX_ELEVATION <= view.elevation <= MAX_ELEVATION
    assert MIN_DISTANCE <= view.distance <= MAX_DISTANCE
    position, rotation = eye_pose(view)
    assert np.isfinite(position).all() and np.isfinite(rotation).all()
    assert checked_view(view.target, view.azimuth, view.elevation, view.distance) == view  # a fixed point


@settings(max_examples=200, deadline=None)
@given(st.floats(-1e3, 1e3), st.floats(-1.5, 1.5), st.floats(0.1, 100.0))
def test_values_within_limits_are_kept(azimuth, elevation, distance):
    view = checked_view((1.0, -2.0, 0.5), azimuth, elevation, distance)
    assert (view.elevation, view.distance) == (elevation, distance)
    assert math.cos(view.azimuth) == pytest.approx(math.cos(azimuth), abs=1e-9)
    assert math.sin(view.azimuth) == pytest.approx(math.sin(azimuth), abs=1e-9)


@settings(max_examples=200, deadline=None)
@given(st.floats(-10.0, 10.0), st.floats(-MAX_ELEVATION, MAX_ELEVATION), st.floats(0.1, 100.0))
def test_mujoco_free_camera_puts_the_eye_at_the_same_place(azimuth, elevation, distance):
    """apply_to converts to MjvCamera's conventions, and view_of (the window's) back."""
    view = checked_view((0.5, -1.0, 0.25), azimuth, elevation, distance)
    model = mujoco.MjModel.from_xml_string("<mujoco/>")
    data, camera, scene = mujoco.MjData(model), mujoco.MjvCamera(), mujoco.MjvScene(model, maxgeom=10)
    apply_to(view, camera)
    mujoco.mjv_updateScene(model, data, mujoco.MjvOption(), None, camera, mujoco.mjtCatBit.mjCAT_ALL, scene)
    position, rotation = eye_pose(view)
    middle = (np.array(scene.camera[0].pos) + np.array(scene.camera[1].pos)) / 2  # the two stereo eyes
    assert middle == pytest.approx(position, abs=1e-5 * max(1.0, distance))  # float32 in the scene
    assert np.array(scene.camera[0].forward) == pytest.approx(rotation[:, 0], abs=1e-5)
    assert np.array(scene.camera[0].up) == pytest.approx(rotation[:, 2], abs=1e-5)
    back = view_of(camera)
    assert back.target == pytest.approx(view.target)
    assert (back.elevation, back.distance) == pytest.approx((view.elevation, view.distance))
    assert math.cos(back.azimuth - view.azimuth) == pytest.approx(1.0)


def test_display_problem():
    assert display_problem({"DISPLAY": ":3"}) == ""
    assert display_problem({"WAYLAND_DISPLAY": "wayland-0"}) == ""
    assert "no display" in display_problem({})


# ---- pictures ---------------------------------------------------------------------------
@pytest.fixture
def gl():
    try:
        context, _ = open_gl_context(8, 8)
    except RenderUnavailable as exc:
        pytest.skip(str(exc))
    context.free()


def test_free_camera_sees_rrbot_and_the_can(gl):
    world = World()
    world.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    world.spawn("rrbot", RRBOT, Pose())
    world.spawn("coke_can", database.model_sdf("coke_can"), Pose(np.array([1.0, 0.0, 0.0])))
    camera = FreeCamera(CameraConfig(width=160, height=120, horizontal_fov=math.radians(60.0), far=1000.0))
    try:
        def picture(view: OrbitView) -> np.ndarray:
            camera.view = view
            world.prepare(camera)
            world.capture(camera)
            return camera.draw()

        robot = picture(checked_view((0.0, 0.0, 1.0), -math.pi / 2, 0.2, 3.0))  # from -y, the arm upright
        assert robot.shape == (120, 160, 3)
        columns = np.nonzero(orange_pixels(robot).any(axis=0))[0]
        assert orange_pixels(robot).sum() > 50 and abs(columns.mean() - 80) < 20  # in the middle
        can = picture(checked_view((1.0, 0.0, 0.06), 0.0, 0.3, 0.6))  # close to the can, from +x
        red_columns = np.nonzero(red_pixels(can).any(axis=0))[0]
        assert red_pixels(can).sum() > 150 and abs(red_columns.mean() - 80) < 10  # 6.6 cm across of 69 cm
        assert (picture(camera.view) == can).all()  # same state, same view: the same picture
        turned = picture(checked_view((0.0, 0.0, 1.0), 0.0, 1.2, 3.0))
        assert (np.abs(turned.astype(int) - robot.astype(int)).sum(axis=2) > 30).sum() > 200
    finally:
        camera.close()


def test_a_still_world_is_not_drawn_again(gl):
    world = World()
    world.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    world.spawn("coke_can", database.model_sdf("coke_can"), Pose(np.array([0.0, 0.0, 0.5])))
    camera = FreeCamera(CameraConfig(width=64, height=48, horizontal_fov=math.radians(60.0), far=1000.0),
                        checked_view((0.0, 0.0, 0.1), 0.0, 0.3, 1.0))
    try:
        def picture() -> np.ndarray:
            world.prepare(camera)
            world.capture(camera)
            return camera.draw()

        falling = picture()
        world.step(200)  # the can falls: drawn again
        landed = picture()
        assert camera.drawn == 2 and (landed != falling).any()
        world.step(3000)  # at rest: settled below a micrometre per frame
        rest = picture()
        world.step(50)
        assert (picture() == rest).all() and camera.drawn == 3  # still: the last picture, not drawn
        camera.view = checked_view((0.0, 0.0, 0.1), 1.0, 0.3, 1.0)
        assert (picture() != rest).any() and camera.drawn == 4  # orbited: drawn
        world.spawn("other", database.model_sdf("coke_can"), Pose(np.array([5.0, 5.0, 0.0])))
        picture()
        assert camera.drawn == 5  # a new model: drawn
    finally:
        camera.close()
