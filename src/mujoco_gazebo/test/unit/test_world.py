import math
from pathlib import Path

import numpy as np
import pytest

from mujoco_gazebo.engine import database
from mujoco_gazebo.engine.frames import Pose, Twist, quat_from_rpy
from mujoco_gazebo.engine.lidar import Lidar, ScanConfig
from mujoco_gazebo.engine.world import World, WorldError

SRC = Path(__file__).resolve().parents[3]
RRBOT = (SRC / "rrbot_description" / "urdf" / "rrbot.urdf").read_text()
WALL = ("<sdf version='1.6'><model name='wall'><static>true</static><link name='l'><collision name='c'>"
        "<pose>0 0 0.5 0 0 0</pose><geometry><box><size>0.1 2 1</size></box></geometry></collision></link></model></sdf>")
BURGER = (SRC / "turtlebot3_description" / "urdf" / "turtlebot3_burger.urdf.xacro").read_text()


@pytest.fixture
def world():
    w = World()
    w.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    return w


def test_can_drops_and_rests_on_ground(world):
    world.spawn("coke_can3", database.model_sdf("coke_can"), Pose([1, 0, 1]))
    world.step(2000)
    pose, twist = world.get_model_state("coke_can3")
    assert abs(pose.position[2]) < 0.005 and math.isclose(pose.position[0], 1.0, abs_tol=1e-3)
    assert np.linalg.norm(twist.linear) < 1e-3


def test_rrbot_collapses_without_controller_and_holds_with_one(world):
    world.spawn("rrbot", RRBOT, Pose())
    world.step(6000)
    pos, _, _ = world.joint_states("rrbot", ["joint1", "joint2"])
    assert abs(pos[0]) > 0.5 or abs(pos[1]) > 0.5
    world.reset_world()
    for j in ("joint1", "joint2"):
        world.set_joint_position("rrbot", j, 0.3, 100.0, 10.0)
    world.step(4000)
    pos, _, _ = world.joint_states("rrbot", ["joint1", "joint2"])
    assert np.allclose(pos, [0.3, 0.3], atol=0.15)  # P-D servo sags under gravity, as without an I term


def test_spawn_and_delete_keep_other_state(world):
    world.spawn("rrbot", RRBOT, Pose())
    world.step(4500)
    before = world.joint_states("rrbot", ["joint1", "joint2"])
    t = world.time
    world.spawn("coke_can3", database.model_sdf("coke_can"), Pose([1, 0, 1]))
    assert world.time == t and np.allclose(world.joint_states("rrbot", ["joint1", "joint2"])[:2], before[:2])
    world.step(100)
    mid = world.joint_states("rrbot", ["joint1", "joint2"])
    world.delete("coke_can3")
    assert np.allclose(world.joint_states("rrbot", ["joint1", "joint2"])[:2], mid[:2])
    assert list(world.models) == ["ground_plane", "rrbot"]


def test_bad_requests_change_nothing(world):
    world.spawn("coke_can3", database.model_sdf("coke_can"), Pose([1, 0, 0.0]))
    world.step(10)
    snapshot = world.data.qpos.copy()
    bad = [lambda: world.spawn("coke_can3", database.model_sdf("coke_can"), Pose()),
           lambda: world.spawn("x", "<robot name='r'><link name='a'/><joint name='j' type='fixed'><parent link='a'/></joint></robot>", Pose()),
           lambda: world.spawn("y", "<sdf><model name='y'><link", Pose()),
           lambda: world.spawn("z", "not xml", Pose()),
           lambda: world.spawn("w", database.model_sdf("coke_can"), Pose([math.nan, 0, 0])),
           lambda: world.set_model_state("nobody", Pose(), Twist()),
           lambda: world.set_model_state("coke_can3", Pose([math.inf, 0, 0]), Twist()),
           lambda: world.set_model_state("coke_can3", Pose(), Twist(), "no_such_frame"),
           lambda: world.delete("nobody"),
           lambda: world.get_model_state("nobody")]
    for call in bad:
        with pytest.raises(WorldError):
            call()
    assert list(world.models) == ["ground_plane", "coke_can3"]
    assert np.array_equal(world.data.qpos, snapshot)


def test_set_model_state_relative_to_model(world):
    world.spawn("rrbot", RRBOT, Pose())
    world.spawn("coke_can3", database.model_sdf("coke_can"), Pose([1, 0, 0]))
    world.set_model_state("rrbot", Pose([2, 0, 0], quat_from_rpy(0, 0, math.pi / 2)), Twist())
    world.set_model_state("coke_can3", Pose([1, 0, 0]), Twist(), "rrbot")
    pose, _ = world.get_model_state("coke_can3")
    assert np.allclose(pose.position, [2, 1, 0], atol=1e-9)
    rel, _ = world.get_model_state("coke_can3", "rrbot")
    assert np.allclose(rel.position, [1, 0, 0], atol=1e-9)
    world.spawn("coke_can4", database.model_sdf("coke_can"), Pose())  # recompiling keeps the moved base
    assert np.allclose(world.get_model_state("rrbot")[0].position, [2, 0, 0])


def test_burger_drives_and_lidar_sees_a_can(world):
    world.spawn("tb3", BURGER, Pose())
    world.spawn("wall", WALL, Pose([1.0, 0, 0]))
    world.step(200)
    lidar = Lidar(ScanConfig())
    import mujoco
    bid = mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, "tb3::base_scan")
    ranges = lidar.scan(world.model, world.data, bid)
    assert len(ranges) == 360 and math.isinf(ranges[180])
    assert math.isclose(ranges[0], 1.0 - 0.05 + 0.032, abs_tol=0.01)  # wall face at 0.95 m, scanner 0.032 m behind base
    for j in ("wheel_left_joint", "wheel_right_joint"):
        world.set_joint_velocity("tb3", j, 0.2 / 0.033, 5.0, 10.0)
    world.step(1500)
    pose, _ = world.get_model_state("tb3")
    assert 0.2 < pose.position[0] < 0.35 and abs(pose.position[1]) < 0.02
