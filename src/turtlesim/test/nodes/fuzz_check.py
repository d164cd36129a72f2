#!/usr/bin/env python3
"""Fuzzing every topic and service handler of turtlesim_node (issue 9).

Random finite, huge, NaN and inf numbers, wild names and odd background params go to
cmd_vel, spawn, kill, clear, reset, set_pen, teleport_absolute and teleport_relative. After
each example the node answers, turtle1 still gets fresh poses (the tick lives), and every
pose is finite, within the walls, with theta in [-pi, pi). A refused request fails with a
message that says why.
"""
import math
import string
import unittest

import rosnode
import rospy
import rostest
from geometry_msgs.msg import Twist
from hypothesis import example, given
from hypothesis import strategies as st
from std_srvs.srv import Empty

from course_testkit.fuzz import (FLOAT32_MAX, as_float32, is_sane_pose, is_wrapped_angle, wild_float32s,
                                 wild_floats, wild_names)
from course_testkit.fuzz import live_node_settings as fuzz
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for
from turtlesim.constants import DEFAULT_BACKGROUND_RGB, WORLD_SIZE
from turtlesim.msg import Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

NODE = "/turtlesim"
REFUSALS = ("non-finite", "invalid turtle name", "already exists", "does not exist")


def sane(p: Pose) -> bool:
    return is_sane_pose(p) and 0.0 <= p.x <= WORLD_SIZE + 1e-4 and 0.0 <= p.y <= WORLD_SIZE + 1e-4


class TurtlesimFuzz(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("turtlesim_fuzz_check")
        rospy.wait_for_service("/turtle1/teleport_absolute", 20)
        cls.pose = TopicRecorder("/turtle1/pose", Pose)
        cls.cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        assert wait_for(lambda: cls.cmd.get_num_connections() > 0 and cls.pose.count > 0, 10)
        cls.spawn = rospy.ServiceProxy("/spawn", Spawn)
        cls.kill = rospy.ServiceProxy("/kill", Kill)
        cls.clear = rospy.ServiceProxy("/clear", Empty)
        cls.reset = rospy.ServiceProxy("/reset", Empty)
        cls.pen = rospy.ServiceProxy("/turtle1/set_pen", SetPen)
        cls.absolute = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        cls.relative = rospy.ServiceProxy("/turtle1/teleport_relative", TeleportRelative)

    def setUp(self):
        self.cmd.publish(Twist())

    def fresh_pose(self, condition=lambda p: True, ticks: int = 3) -> Pose:
        """A pose published `ticks` ticks after now that meets `condition`; fails if the tick died."""
        start = self.pose.count
        pose = self.pose.wait(lambda p: self.pose.count >= start + ticks and condition(p), timeout=3.0)
        self.assertIsNotNone(pose, "turtlesim published no fitting pose: the tick died or the request was lost"
                             " (last pose %s)" % self.pose.last)
        return pose

    def assert_healthy(self, condition=lambda p: True) -> Pose:
        pose = self.fresh_pose(condition)
        self.assertTrue(sane(pose), "insane pose: %s" % pose)
        self.assertTrue(rosnode.rosnode_ping(NODE, max_count=1), "turtlesim_node does not answer")
        rospy.wait_for_service("/spawn", 5)
        return pose

    def assert_refused(self, err: Exception) -> None:
        self.assertTrue(any(r in str(err) for r in REFUSALS), "unclear refusal: %s" % err)

    @fuzz(60)
    @given(wild_floats(), wild_floats(), wild_floats())
    @example(1e308, 0.0, 0.0)  # OverflowError packing the pose killed the tick
    @example(0.0, 0.0, 1e18)  # theta -4.0
    def test_cmd_vel(self, vx, vy, w):
        twist = Twist()
        twist.linear.x, twist.linear.y, twist.angular.z = vx, vy, w
        self.cmd.publish(twist)
        if all(math.isfinite(v) for v in (vx, vy, w)):  # taken, held within float32's range
            want = as_float32(w)
            self.assert_healthy(lambda p: p.angular_velocity == want)
        else:  # dropped with a warning
            self.assert_healthy()

    @fuzz(40)
    @given(wild_float32s(), wild_float32s(), wild_float32s())
    @example(FLOAT32_MAX, -FLOAT32_MAX, FLOAT32_MAX)
    def test_teleport_absolute(self, x, y, theta):
        try:
            self.absolute(x, y, theta)
        except rospy.ServiceException as err:
            self.assertFalse(all(math.isfinite(v) for v in (x, y, theta)), err)
            self.assert_refused(err)
            self.assert_healthy()
            return
        want_x = min(max(x, 0.0), WORLD_SIZE)
        want_y = min(max(y, 0.0), WORLD_SIZE)
        pose = self.assert_healthy(lambda p: abs(p.x - want_x) < 1e-4 and abs(p.y - want_y) < 1e-4)
        if abs(theta) < 1e6:
            self.assertAlmostEqual(math.cos(pose.theta), math.cos(theta), places=4)
            self.assertAlmostEqual(math.sin(pose.theta), math.sin(theta), places=4)

    @fuzz(40)
    @given(wild_float32s(), wild_float32s())
    @example(FLOAT32_MAX, FLOAT32_MAX)
    def test_teleport_relative(self, linear, angular):
        try:
            self.relative(linear, angular)
        except rospy.ServiceException as err:
            self.assertFalse(math.isfinite(linear) and math.isfinite(angular), err)
            self.assert_refused(err)
        self.assert_healthy()

    @fuzz(25)
    @given(wild_names(), wild_float32s(), wild_float32s(), wild_float32s())
    @example("/turtle1", 1.0, 1.0, 0.0)  # a second spelling of turtle1's namespace
    @example("turtle9\n", 1.0, 1.0, 0.0)
    @example("x" * 5000, 1.0, 1.0, 0.0)
    @example("far", FLOAT32_MAX, -FLOAT32_MAX, FLOAT32_MAX)
    def test_spawn_and_kill(self, name, x, y, theta):
        try:
            given_name = self.spawn(x, y, theta, name).name
        except rospy.ServiceException as err:
            self.assert_refused(err)
            self.assert_healthy()
            return
        self.assertTrue(all(math.isfinite(v) for v in (x, y, theta)), "spawned with (%r, %r, %r)" % (x, y, theta))
        self.assertTrue(given_name == name or not name, (name, given_name))
        spawned = TopicRecorder(given_name + "/pose", Pose)
        try:
            pose = spawned.wait(timeout=10.0)
            self.assertIsNotNone(pose, "no pose from the spawned turtle [%s]" % given_name)
            self.assertTrue(sane(pose), "insane pose of [%s]: %s" % (given_name, pose))
        finally:
            spawned.unregister()
            self.kill(given_name)
        self.assert_healthy()

    @fuzz(30)
    @given(wild_names().filter(lambda n: n not in ("turtle1", "/turtle1")))
    def test_kill_unknown(self, name):
        with self.assertRaises(rospy.ServiceException) as caught:
            self.kill(name)
        self.assert_refused(caught.exception)
        self.assert_healthy()

    @fuzz(30)
    @given(*[st.integers(0, 255)] * 5)
    def test_set_pen(self, r, g, b, width, off):
        self.pen(r, g, b, width, off)
        self.assert_healthy()

    @fuzz(20)
    @given(st.lists(st.one_of(wild_floats(), st.integers(-10**6, 10**6), st.text(string.printable, max_size=5), st.booleans()),
                    min_size=3, max_size=3), st.booleans())
    def test_clear_and_reset_with_odd_backgrounds(self, values, reset):
        for channel, value in zip("rgb", values):
            rospy.set_param("%s/background_%s" % (NODE, channel), value)
        try:
            (self.reset if reset else self.clear)()
        finally:
            for channel, value in zip("rgb", DEFAULT_BACKGROUND_RGB):
                rospy.set_param("%s/background_%s" % (NODE, channel), value)
        self.assert_healthy()


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "turtlesim_fuzz", TurtlesimFuzz)
