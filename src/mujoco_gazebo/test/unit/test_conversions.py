"""Sim-time stamps: exact multiples of the step, as Gazebo's integer clock gives them."""
import mujoco

from mujoco_gazebo.ros.conversions import stamp_from_sim


def test_float_sum_of_steps_stamps_the_whole_millisecond():
    t = 0.0
    for _ in range(1080):  # what MuJoCo accumulates after 1080 steps of 1 ms: 1.0799999999999919
        t += 0.001
    assert t < 1.08
    stamp = stamp_from_sim(t)
    assert (stamp.secs, stamp.nsecs) == (1, 80000000)


def test_every_clock_tick_of_a_stepping_world_is_on_the_step_grid():
    model = mujoco.MjModel.from_xml_string("<mujoco><option timestep='0.001'/></mujoco>")
    data = mujoco.MjData(model)
    for _ in range(2000):
        mujoco.mj_step(model, data, nstep=5)
        assert stamp_from_sim(data.time).nsecs % 1000000 == 0


def test_negative_and_carry():
    assert stamp_from_sim(-0.5).to_nsec() == 0
    stamp = stamp_from_sim(2.9999999999)
    assert (stamp.secs, stamp.nsecs) == (3, 0)
