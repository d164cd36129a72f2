"""The cause of rrbot_camera.test's flake ("still arm, same picture": 104 changed pixels): one
slow joint_states sample is not a still arm. The simulated RRBot, sampled at its 50 Hz, swings
through zero velocity while its camera still moves; StillnessDetector waits for a whole slow
window, after which the camera stays put."""
import math
from pathlib import Path

import mujoco
import numpy as np

from mujoco_gazebo.engine import database
from mujoco_gazebo.engine.frames import Pose
from mujoco_gazebo.engine.settling import StillnessDetector
from mujoco_gazebo.engine.world import World

RRBOT = (Path(__file__).resolve().parents[3] / "rrbot_description" / "urdf" / "rrbot.urdf").read_text()


def test_still_arm_keeps_its_camera_still():
    world = World()
    world.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    world.spawn("rrbot", RRBOT, Pose())
    camera = mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, "rrbot::camera_link")
    world.step(3000)  # collapsed under gravity, as the test finds it
    for joint, target in (("joint1", math.pi / 2), ("joint2", 0.0)):
        world.set_joint_position("rrbot", joint, target, 100.0, 10.0)  # the plugin's default gains
    detector = StillnessDetector()
    while not detector.still:
        assert world.time < 30.0, "the arm never settled"
        world.step(20)  # joint_states at 50 Hz
        detector.add(world.time, world.joint_states("rrbot", ["joint1", "joint2"])[1])
    settled = world.body_pose(camera)
    world.step(300)  # the test's next frame is 0.2 s later (and a frame period)
    later = world.body_pose(camera)
    assert np.linalg.norm(later.position - settled.position) < 1e-3
    assert np.linalg.norm(later.orientation - settled.orientation) < 1e-3


def test_detector_needs_a_whole_slow_window():
    d = StillnessDetector(window=1.0, speed=0.005)
    for i in range(60):
        d.add(0.02 * i, [0.001 if i % 20 else 0.5])  # a fast sample every 0.4 s
    assert not d.still
    for i in range(60, 120):
        d.add(0.02 * i, [0.001])
    assert d.still
    d.add(0.0, [0.0])  # a reset: time went back
    assert not d.still
