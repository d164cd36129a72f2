"""Queries answer the current state: after stepping, a body's pose/velocity are those of the
current qpos/qvel, so spawning or deleting another model (which recomputes the kinematics)
leaves every other model's reported state exactly as it was, as Gazebo does."""
import numpy as np

from mujoco_gazebo.engine import database
from mujoco_gazebo.engine.frames import Pose
from mujoco_gazebo.engine.world import World

BOX = ("<robot name='b'><link name='l'><inertial><mass value='0.5'/><inertia ixx='1e-3' iyy='1e-3' izz='1e-3' "
       "ixy='0' ixz='0' iyz='0'/></inertial><collision><geometry><box size='0.1 0.1 0.1'/></geometry></collision>"
       "</link></robot>")


def falling_world() -> World:
    world = World()
    world.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    world.spawn("faller", BOX, Pose([0, 0, 5]))
    world.step(7)
    return world


def test_pose_and_velocity_are_those_after_the_last_step():
    world = falling_world()
    pose, twist = world.get_model_state("faller")
    # semi-implicit Euler, 7 steps of 1 ms from rest: v = -7 g dt, z drop = g dt^2 (1 + ... + 7)
    g, dt = 9.81, world.timestep
    assert np.isclose(twist.linear[2], -7 * g * dt, atol=1e-9)
    assert np.isclose(pose.position[2], 5 - 28 * g * dt * dt, atol=1e-9)


def test_spawn_and_delete_elsewhere_leave_a_falling_model_exactly_as_reported():
    world = falling_world()
    before = world.get_model_state("faller")
    world.spawn("visitor", BOX, Pose([1, 1, 0.5]))
    during = world.get_model_state("faller")
    world.delete("visitor")
    after = world.get_model_state("faller")
    for state in (during, after):
        assert np.array_equal(state[0].position, before[0].position)
        assert np.array_equal(state[0].orientation, before[0].orientation)
        assert np.array_equal(state[1].linear, before[1].linear)
        assert np.array_equal(state[1].angular, before[1].angular)


def test_link_states_match_model_states_after_stepping():
    world = falling_world()
    names, poses, _ = world.link_states()
    _, model_poses, _ = world.model_states()
    assert np.array_equal(poses[names.index("faller::l")].position, model_poses[1].position)
    assert np.array_equal(poses[names.index("faller::l")].position, world.data.qpos[:3])
