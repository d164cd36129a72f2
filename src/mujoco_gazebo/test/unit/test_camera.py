"""Camera rendering without ROS: optics, GL backend choice and fallback, and rendered frames of
tiny models (skipped, with the reason, only when no headless GL backend can be opened)."""
import math
from pathlib import Path

import mujoco
import numpy as np
import pytest

from mujoco_gazebo.engine import database
from mujoco_gazebo.engine.appearance import urdf_link_colours
from mujoco_gazebo.engine.camera import BodyCamera, CameraConfig, RenderUnavailable, backend_order, open_gl_context
from mujoco_gazebo.engine.frames import Pose
from mujoco_gazebo.engine.world import World

RRBOT = (Path(__file__).resolve().parents[3] / "rrbot_description" / "urdf" / "rrbot.urdf").read_text()

# An eye 1 m up, pitched 30 degrees down and turned 15 degrees left, over a large green floor
# with a red box and a blue ball ahead; `housing` wraps the eye in a box, as RRBot's camera_link.
SCENE = """<mujoco><visual><global offwidth="64" offheight="48"/></visual><worldbody>
  <light pos="0 0 5" dir="0 0 -1" directional="true"/>
  <geom type="plane" size="100 100 .1" rgba=".3 .6 .3 1"/>
  <geom type="box" pos="2 0.4 0.4" size=".2 .2 .4" rgba="1 0 0 1"/>
  <geom type="sphere" pos="2.2 -0.3 0.3" size=".3" rgba="0 0 1 1"/>
  <body name="eye" pos="0 0 1" euler="0 30 15">
    {housing}
    <camera name="reference" xyaxes="0 -1 0 0 0 1" fovy="{fovy}"/>
  </body></worldbody></mujoco>"""


def scene_model(config: CameraConfig, housing: str = ""):
    model = mujoco.MjModel.from_xml_string(SCENE.format(housing=housing, fovy=math.degrees(config.vertical_fov)))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data, mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "eye")


@pytest.fixture
def config():
    return CameraConfig(width=160, height=120, horizontal_fov=1.3962634)


@pytest.fixture
def camera(config):
    cam = BodyCamera(config)
    model, data, eye = scene_model(config)
    try:
        cam.render(model, data, eye)
    except RenderUnavailable as exc:
        pytest.skip("no headless OpenGL here: %s" % exc)
    yield cam
    cam.close()


def reference_render(model, data, config):
    """The same view through MuJoCo's own fixed camera (on the GL context left current)."""
    model.vis.global_.offwidth, model.vis.global_.offheight = config.width, config.height
    context = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_100)
    try:
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, context)
        scene = mujoco.MjvScene(model, maxgeom=100)
        for flag in (mujoco.mjtRndFlag.mjRND_SHADOW, mujoco.mjtRndFlag.mjRND_REFLECTION, mujoco.mjtRndFlag.mjRND_HAZE):
            scene.flags[flag] = False
        cam = mujoco.MjvCamera()
        cam.type, cam.fixedcamid = mujoco.mjtCamera.mjCAMERA_FIXED, 0
        mujoco.mjv_updateScene(model, data, mujoco.MjvOption(), None, cam, mujoco.mjtCatBit.mjCAT_ALL, scene)
        rect = mujoco.MjrRect(0, 0, config.width, config.height)
        mujoco.mjr_render(rect, scene, context)
        pixels = np.empty((config.height, config.width, 3), dtype=np.uint8)
        mujoco.mjr_readPixels(pixels, None, rect, context)
        return np.flipud(pixels)
    finally:
        context.free()


def distinct_colours(img: np.ndarray) -> int:
    return len(np.unique(img.reshape(-1, 3), axis=0))


# ---- optics and backend choice ------------------------------------------------------------
def test_intrinsics_follow_gazebo_ros_camera():
    cfg = CameraConfig(width=800, height=800, horizontal_fov=1.3962634)
    fx, fy, cx, cy = cfg.intrinsics()
    assert fx == pytest.approx(400 / math.tan(0.6981317)) and fy == fx
    assert (cx, cy) == (400.5, 400.5)
    assert cfg.vertical_fov == pytest.approx(1.3962634)          # square image: same fov both ways
    assert CameraConfig(width=320, height=240).vertical_fov < 1.3962634


@pytest.mark.parametrize("kwargs", [dict(width=0), dict(height=-1), dict(horizontal_fov=0.0),
                                    dict(horizontal_fov=4.0), dict(near=0.0), dict(near=5.0, far=1.0)])
def test_bad_config_is_refused(kwargs):
    with pytest.raises(ValueError):
        CameraConfig(**kwargs)


def test_backend_order():
    assert backend_order("") == ["egl", "osmesa"]
    assert backend_order("OSMesa") == ["osmesa", "egl"]
    assert backend_order("glfw") == ["egl", "osmesa"]  # needs a display: never tried headless
    assert backend_order("disable") == [] and backend_order("0") == []


def test_disabled_rendering_fails_cleanly_every_time(config):
    with pytest.raises(RenderUnavailable, match="disabled"):
        open_gl_context(64, 48, requested="off")
    cam = BodyCamera(config)
    model, data, eye = scene_model(config)
    import os
    saved = os.environ.get("MUJOCO_GL")
    os.environ["MUJOCO_GL"] = "disable"
    try:
        for _ in range(2):  # the failure is remembered, not retried
            with pytest.raises(RenderUnavailable):
                cam.render(model, data, eye)
    finally:
        if saved is None:
            del os.environ["MUJOCO_GL"]
        else:
            os.environ["MUJOCO_GL"] = saved
    cam.close()
    cam.close()


# ---- rendered frames ----------------------------------------------------------------------
def test_frame_is_a_picture_of_the_scene(camera, config):
    model, data, eye = scene_model(config)
    img = camera.render(model, data, eye)
    assert img.shape == (120, 160, 3) and img.dtype == np.uint8
    assert distinct_colours(img) > 20 and img.std() > 10
    r, g, b = (img[..., i].astype(int) for i in range(3))
    red, blue = (r > 50) & (r > 3 * g) & (r > 3 * b), (b > 50) & (b > 3 * r) & (b > 3 * g)
    assert red.sum() > 50 and blue.sum() > 50
    # turned 15 degrees left: the red box (y = +0.4, left) is left of the blue ball (y = -0.3)
    assert np.nonzero(red)[1].mean() < np.nonzero(blue)[1].mean()
    assert camera.backend in ("egl", "osmesa")


def test_view_matches_mujocos_fixed_camera(camera, config):
    """Looking along the body's +x with +z up at the configured fov is exactly the MJCF camera
    with xyaxes (-y, +z) and the matching vertical fov."""
    model, data, eye = scene_model(config)
    img = camera.render(model, data, eye)
    ref = reference_render(model, data, config)
    sky = (ref == 0).all(axis=2)
    assert sky.mean() < 0.5  # the comparison covers most of the frame
    diff = np.abs(img.astype(int) - ref.astype(int))[~sky]
    assert diff.mean() < 2.0, diff.mean()


def test_own_housing_is_hidden(camera, config):
    model, data, eye = scene_model(config, housing='<geom type="box" size=".05 .05 .05" rgba="1 1 0 1"/>')
    img = camera.render(model, data, eye)
    yellow = (img[..., 0] > 120) & (img[..., 1] > 120) & (img[..., 2] < 60)
    assert yellow.mean() < 0.01 and distinct_colours(img) > 20


def test_new_model_and_moving_body_change_the_picture(camera, config):
    model, data, eye = scene_model(config)
    before = camera.render(model, data, eye).astype(int)
    model.body_quat[eye] = [1, 0, 0, 0]  # no joints: turn the eye level by editing the model
    mujoco.mj_forward(model, data)
    level = camera.render(model, data, eye).astype(int)
    assert np.abs(level - before).mean() > 10
    other, other_data, other_eye = scene_model(config)
    again = camera.render(other, other_data, other_eye).astype(int)  # a recompiled model: new MjrContext
    assert np.abs(again - before).mean() < 2.0


def test_image_larger_than_the_models_offscreen_buffer(config):
    cam = BodyCamera(CameraConfig(width=200, height=150))
    model, data, eye = scene_model(config)  # offwidth 64 x offheight 48
    try:
        img = cam.render(model, data, eye)
    except RenderUnavailable as exc:
        pytest.skip("no headless OpenGL here: %s" % exc)
    finally:
        cam.close()
    assert img.shape == (150, 200, 3) and distinct_colours(img) > 20
    assert (model.vis.global_.offwidth, model.vis.global_.offheight) == (64, 48)  # left as it was


def test_rrbot_camera_sees_a_coke_can_spawned_below_it(camera):
    world = World()
    world.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    world.spawn("rrbot", RRBOT, Pose())
    eye = mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, "rrbot::camera_link")
    for joint, angle in (("joint1", math.pi / 2), ("joint2", 0.0)):  # arm level, camera looking down
        world.set_joint_position("rrbot", joint, angle, 100.0, 10.0)
    world.step(3000)
    empty = camera.render(world.model, world.data, eye).astype(int)
    assert (camera.render(world.model, world.data, eye) == empty).all()  # same state, same picture
    position = world.data.xpos[eye].copy()
    position[2] = 0.0
    world.spawn("coke_can", database.model_sdf("coke_can"), Pose(position))
    with_can = camera.render(world.model, world.data, eye).astype(int)
    changed = (np.abs(with_can - empty).sum(axis=2) > 30).sum()
    assert changed > 20, changed  # the can's top is ~9 px across from 1.6 m


# ---- URDF colours -------------------------------------------------------------------------
def test_urdf_link_colours():
    colours = urdf_link_colours(RRBOT)
    orange = (1.0, 0.423529411765, 0.0392156862745, 1.0)
    assert colours["link1"] == pytest.approx(orange)
    assert colours["link3"] == pytest.approx(orange)  # <material name="orange"/> by reference
    assert colours["link2"] == (0.0, 0.0, 0.0, 1.0)
    assert colours["camera_link"] == pytest.approx((0.8, 0.0, 0.0, 1.0))
    assert "world" not in colours
    assert urdf_link_colours("<robot><link") == {}
    assert urdf_link_colours("<robot><link name='a'><visual><material name='m'><color rgba='1 x 0 1'/>"
                             "</material></visual></link></robot>") == {}


def test_world_paints_urdf_links():
    world = World()
    world.spawn("rrbot", RRBOT, Pose())
    link2 = mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, "rrbot::link2")
    rgba = [world.model.geom_rgba[g] for g in range(world.model.ngeom) if world.model.geom_bodyid[g] == link2]
    assert rgba and all(tuple(c) == (0, 0, 0, 1) for c in rgba)
