#!/usr/bin/env python3
"""Milestone `gazebo_rrbot` (003 Part II, tasks 1-3), run with the text's own commands, plus bad input.

This milestone checks the course workspace (the MuJoCo-backed Gazebo API, spawn_model, the model
database and the RRBot world), not a student package."""
import math
import subprocess
import time

import rospy
import rostest
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import DeleteModel, GetModelState, GetWorldProperties, SetModelState, SpawnModel
from geometry_msgs.msg import Pose
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

from course_rospy import quick_exit
from course_milestones import guard
from course_format import causes
from course_milestones.milestone_case import MilestoneCase, failure
from course_milestones.trusted import GAZEBO
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

SET_CAN = ("{model_state: { model_name: coke_can3, pose: { position: { x: 0.3, y: 0.2 ,z: 0 }, orientation: "
           "{x: 0, y: 0, z: 0, w: 1.0 } }, twist: { linear: {x: 0.0 , y: 0 ,z: 0 } , angular: { x: 0.0 , y: 0 , "
           "z: 0.0 } }, reference_frame: world } }")


def wait_until(pred, timeout=40.0, what="condition"):
    end = time.monotonic() + timeout
    while time.monotonic() < end and not rospy.is_shutdown():
        value = pred()
        if value:
            return value
        time.sleep(0.05)
    raise failure(causes.finding("course_tools", "timed out waiting for " + what))


@guard.judged  # a violation of the trust policy fails the test, first
class RRBotWorld(MilestoneCase):
    failure_cause = "course_tools"  # the course's own tools: unittest's words, this cause

    def setUp(self):
        rospy.wait_for_service("/gazebo/get_model_state", 60)
        self.get = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        self.spawn = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)
        self.set = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)
        self.delete = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)
        self.props = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)
        wait_until(lambda: "rrbot" in self.props().model_names, what="rrbot spawned")

    def can(self):
        return self.get("coke_can3", "world").pose.position

    def test_text_003(self):
        # Task 1: the arm collapses under gravity within seconds.
        wait_until(lambda: max(abs(q) for q in rospy.wait_for_message("/rrbot/joint_states", JointState, 10).position) > 0.5,
                   timeout=60, what="the arm to collapse")
        # Task 2: the text's spawn command; the can drops and rests on the ground.
        out = subprocess.run("rosrun gazebo_ros spawn_model -database coke_can -sdf -model coke_can3 -x 1 -z 1",
                             shell=True, capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 0, causes.finding("course_tools", out.stdout + out.stderr))
        wait_until(lambda: self.get("coke_can3", "").success and self.can().z < 0.01
                   and abs(self.get("coke_can3", "").twist.linear.z) < 1e-3, what="the can to rest")
        states = rospy.wait_for_message("/gazebo/model_states", ModelStates, 10)
        self.assertEqual(states.name[:3], ["ground_plane", "rrbot", "coke_can3"])
        pose = states.pose[states.name.index("coke_can3")]
        self.assertAlmostEqual(pose.position.x, 1.0, delta=0.01)
        self.assertAlmostEqual(pose.orientation.w, 1.0, delta=0.01)
        # Task 3: the text's set_model_state call, verbatim. The hanging arm may nudge the can right
        # after, so look for the set pose in the model_states stream rather than in one later read.
        states = TopicRecorder("/gazebo/model_states", ModelStates)

        def can_at_target():
            for msg in states.messages:
                if "coke_can3" in msg.name:
                    p = msg.pose[msg.name.index("coke_can3")].position
                    if abs(p.x - 0.3) < 0.01 and abs(p.y - 0.2) < 0.01:
                        return True
            return False

        out = subprocess.run(["rosservice", "call", "/gazebo/set_model_state", SET_CAN], capture_output=True,
                             text=True, timeout=30)
        self.assertIn("success: True", out.stdout, causes.finding("course_tools", out.stdout + out.stderr))
        self.assertTrue(wait_for(can_at_target, 10),
                        causes.finding("course_tools", "the can never showed at (0.3, 0.2) in /gazebo/model_states"))
        states.unregister()
        # Bad input: clear failures, nothing else changes (the can may be nudged by the hanging arm,
        # so the world's model list and RRBot's base are what must stay).
        base_before = self.get("rrbot", "").pose.position
        nan_pose = Pose()
        nan_pose.position.x = math.nan
        for resp in (self.spawn("coke_can3", "<sdf version='1.6'><model name='c'><link name='l'/></model></sdf>", "", Pose(), ""),
                     self.spawn("bad_urdf", "<robot name='r'><link name='a'>", "", Pose(), ""),
                     self.spawn("bad_sdf", "<sdf><model name='x'></model></sdf>", "", Pose(), ""),
                     self.spawn("nan_can", "<sdf version='1.6'><model name='c'><link name='l'/></model></sdf>", "", nan_pose, ""),
                     self.delete("nobody")):
            self.assertFalse(resp.success)
            self.assertTrue(resp.status_message)
        resp = self.get("nobody", "")
        self.assertFalse(resp.success)
        self.assertIn("nobody", resp.status_message)
        out = subprocess.run("rosrun gazebo_ros spawn_model -database no_such_model -sdf -model m", shell=True,
                             capture_output=True, text=True, timeout=60)
        self.assertNotEqual(out.returncode, 0)
        self.assertIn("not in the model database", out.stdout + out.stderr)
        self.assertEqual(self.props().model_names, ["ground_plane", "rrbot", "coke_can3"])
        base_after = self.get("rrbot", "").pose.position
        self.assertEqual((base_after.x, base_after.y, base_after.z), (base_before.x, base_before.y, base_before.z))
        # Strike: move RRBot with set_model_state (as the text does) so that, hanging down, its
        # swinging link3 passes 5 cm above the ground right over the can at (0.3, 0.2): joint2
        # is then 1.05 m up and link3 reaches 0.95 m below it, clear of the ground but not of the can.
        lowered = SetModelState._request_class()
        lowered.model_state.model_name = "rrbot"
        lowered.model_state.pose.position.x = 0.3
        lowered.model_state.pose.orientation.w = 1.0
        self.assertTrue(self.set(lowered).success)
        j1 = rospy.Publisher("/rrbot/joint1_position_controller/command", Float64, queue_size=1, latch=True)
        j2 = rospy.Publisher("/rrbot/joint2_position_controller/command", Float64, queue_size=1, latch=True)
        j1.publish(math.pi)
        j2.publish(-0.8)
        def at_start():  # both joints settled: joint1 hanging down (pi), joint2 at -0.8
            js = rospy.wait_for_message("/rrbot/joint_states", JointState, 10)
            q1, q2 = js.position[0], js.position[1]
            return (abs(math.remainder(q1 - math.pi, 2 * math.pi)) < 0.05 and abs(q2 + 0.8) < 0.05
                    and max(abs(v) for v in js.velocity) < 0.05)

        wait_until(at_start, what="the arm to reach its start")
        self.assertTrue(self.set(_can_state()).success)
        start = self.get("coke_can3", "world").pose
        j2.publish(0.8)

        def struck():
            now = self.get("coke_can3", "world").pose
            shifted = math.hypot(now.position.x - start.position.x, now.position.y - start.position.y)
            tilt = 1.0 - abs(now.orientation.w * start.orientation.w + now.orientation.x * start.orientation.x
                             + now.orientation.y * start.orientation.y + now.orientation.z * start.orientation.z)
            return (shifted > 0.02 or tilt > 0.05) and now  # pushed away, or knocked over

        self.assertTrue(wait_until(struck, what="the arm to strike the can"))


def _can_state():
    from gazebo_msgs.msg import ModelState
    s = ModelState(model_name="coke_can3", reference_frame="world")
    s.pose.position.x, s.pose.position.y, s.pose.orientation.w = 0.3, 0.2, 1.0
    return s


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("gazebo_rrbot_check")
    guard.install([GAZEBO])  # before any student code: believe only this simulator
    rostest.rosrun("course_milestones", "gazebo_rrbot", RRBotWorld)
