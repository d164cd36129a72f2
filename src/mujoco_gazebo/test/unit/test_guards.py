"""Issue 9: the world refuses states the physics cannot hold, undoes a step that diverges
anyway (time runs on, nothing jumps to its spawn pose), and spawn/delete leave nothing behind."""
import math
from pathlib import Path

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from course_testkit.fuzz import wild_floats
from mujoco_gazebo.engine import database
from mujoco_gazebo.engine.frames import Pose, Twist, normalize_quat
from mujoco_gazebo.engine.limits import WORLD_BOUND_M, pose_problem, twist_problem
from mujoco_gazebo.engine.world import World, WorldError

SRC = Path(__file__).resolve().parents[3]
RRBOT = (SRC / "rrbot_description" / "urdf" / "rrbot.urdf").read_text()
CAN = database.model_sdf("coke_can")


@pytest.fixture(autouse=True)
def quiet_mujoco():
    old = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda text: None)
    yield
    mujoco.set_mju_user_warning(old)


@pytest.fixture
def world():
    w = World()
    w.spawn("ground_plane", database.model_sdf("ground_plane"), Pose())
    w.spawn("can", CAN, Pose([1, 0, 0]))
    w.spawn("other", CAN, Pose([-1, 0, 0]))
    w.spawn("rrbot", RRBOT, Pose([0, 2, 0]))
    w.step(300)
    return w


@pytest.mark.parametrize("position", [[1e30, 0, 0], [math.nan, 0, 0], [0, -math.inf, 0], [0, 0, 2 * WORLD_BOUND_M]])
def test_unholdable_positions_are_refused(world, position):
    before = world.data.qpos.copy()
    with pytest.raises(WorldError, match="not finite|outside the world"):
        world.set_model_state("can", Pose(position), Twist())
    with pytest.raises(WorldError):
        world.spawn("new", CAN, Pose(position))
    assert np.array_equal(world.data.qpos, before) and "new" not in world.models


def test_unholdable_twists_and_commands_are_refused(world):
    for twist in (Twist([1e30, 0, 0]), Twist([0, 0, 0], [0, math.nan, 0]), Twist([100, 0, 0])):
        with pytest.raises(WorldError):
            world.set_model_state("can", Pose([1, 0, 0]), twist)
    for value in (1e30, math.inf, math.nan):
        with pytest.raises(WorldError):
            world.set_joint_effort("rrbot", "joint1", value)


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.lists(wild_floats(), min_size=4, max_size=4))
def test_quaternions_normalise_without_overflow(q):
    unit = normalize_quat(np.array(q)) if all(map(math.isfinite, q)) else None
    if unit is not None:
        assert math.isclose(float(np.linalg.norm(unit)), 1.0, rel_tol=1e-9)
    assert bool(pose_problem([0, 0, 0], q)) == (unit is None)


def test_zero_quaternion_means_no_rotation_as_in_gazebo():
    assert pose_problem([0, 0, 0], [0, 0, 0, 0]) == ""
    assert np.array_equal(normalize_quat(np.zeros(4)), [1, 0, 0, 0])


def test_twist_bounds():
    assert twist_problem([1e200, 1e200, 0], [0, 0, 0])  # no overflow to a silent pass
    assert twist_problem([3, 4, 0], [0, 0, 5]) == ""


def test_a_diverging_step_is_undone_and_time_runs_on(world):
    """A state that slips past the limits (placed directly) makes MuJoCo diverge: MuJoCo's reset
    would set the time to 0 and every model to its spawn pose; the world restores instead."""
    other_before = world.get_model_state("other")[0].position.copy()
    can_before = world.get_model_state("can")[0].position.copy()
    t = world.time
    world._place(world.models["can"], Pose([1e30, 0, 0]), Twist())
    world.step(5)
    assert world.divergences == 1 and "QPOS" in world.last_divergence and "[can]" in world.last_divergence
    assert math.isclose(world.time, t + 5 * world.timestep)
    assert np.allclose(world.get_model_state("can")[0].position, can_before, atol=1e-3)
    assert np.allclose(world.get_model_state("other")[0].position, other_before, atol=1e-3)
    times = []
    for _ in range(200):
        world.step(5)
        times.append(world.time)
    assert all(b > a for a, b in zip(times, times[1:])) and world.divergences == 1


def test_a_state_that_keeps_diverging_comes_to_rest(world):
    world._place(world.models["can"], Pose([1, 0, 0.5]), Twist([0, 0, -1e9]))
    t = world.time
    for _ in range(3):
        world.step(5)
    assert world.divergences >= 1 and world.time > t
    assert np.all(np.isfinite(world.data.qpos)) and np.all(np.isfinite(world.data.qvel))


def test_spawn_delete_rounds_leave_no_bodies_frames_or_actuators(world):
    world.set_model_state("rrbot", Pose([0, 3, 0]), Twist())  # fixed model moved: survives rebuilds
    bodies, nbody, actuators = len(world.spec.bodies), world.model.nbody, world.model.nu
    for _ in range(3):
        for i in range(40):
            world.spawn("tmp%d" % i, RRBOT if i % 10 == 0 else CAN, Pose([0.3 * i, 5, 0]))
        world.step(10)
        for i in range(40):
            world.delete("tmp%d" % i)
    assert list(world.models) == ["ground_plane", "can", "other", "rrbot"]
    assert len(world.spec.frames) == 1  # the one shared frame; one per spawn before
    assert (len(world.spec.bodies), world.model.nbody, world.model.nu) == (bodies, nbody, actuators)
    assert world._deletions < 120  # the spec was rebuilt: MjSpec's memory for deletions is gone
    assert np.allclose(world.get_model_state("rrbot")[0].position, [0, 3, 0])
