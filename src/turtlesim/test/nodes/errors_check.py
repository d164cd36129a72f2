#!/usr/bin/env python3
"""Bad input to turtlesim_node: refused with a message, node alive, pose finite."""
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty

from turtlesim.msg import Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative
from course_testkit.fuzz import is_sane_pose
from course_checks.recorders import RosoutRecorder, TopicRecorder
from course_checks.waiting import wait_for


class TurtlesimErrors(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("turtlesim_errors_check")
        rospy.wait_for_service("/turtle1/teleport_absolute", 20)
        cls.rosout = RosoutRecorder()
        cls.pose = TopicRecorder("/turtle1/pose", Pose)
        cls.cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=10)
        assert wait_for(lambda: cls.cmd.get_num_connections() > 0, 10)

    def assert_alive_and_finite(self):
        count = self.pose.count
        p = self.pose.wait(lambda p: self.pose.count > count + 2)
        self.assertIsNotNone(p, "turtlesim stopped publishing")
        self.assertTrue(is_sane_pose(p), p)
        rospy.ServiceProxy("/clear", Empty)()

    def test_nan_and_inf_cmd_vel_are_ignored_with_a_warning(self):
        for bad in (float("nan"), float("inf"), -float("inf")):
            t = Twist()
            t.linear.x, t.angular.z = 1.0, bad
            self.cmd.publish(t)
        self.assertTrue(self.rosout.wait_for_text("cmd_vel rejected: non-finite", level=4))
        self.assert_alive_and_finite()

    def test_non_finite_teleports_fail_with_a_message(self):
        absolute = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        relative = rospy.ServiceProxy("/turtle1/teleport_relative", TeleportRelative)
        with self.assertRaisesRegex(rospy.ServiceException, "teleport_absolute rejected: non-finite x=inf"):
            absolute(float("inf"), 1.0, 0.0)
        with self.assertRaisesRegex(rospy.ServiceException, "non-finite angular=nan"):
            relative(1.0, float("nan"))
        self.assert_alive_and_finite()

    def test_non_finite_spawn_fails_and_adds_nothing(self):
        spawn = rospy.ServiceProxy("/spawn", Spawn)
        with self.assertRaisesRegex(rospy.ServiceException, "non-finite theta=nan"):
            spawn(1.0, 1.0, float("nan"), "nanny")
        with self.assertRaisesRegex(rospy.ServiceException, "does not exist"):
            rospy.ServiceProxy("/kill", Kill)("nanny")
        self.assert_alive_and_finite()

    def test_invalid_and_duplicate_names(self):
        spawn = rospy.ServiceProxy("/spawn", Spawn)
        with self.assertRaisesRegex(rospy.ServiceException, r"A turtled named \[turtle1\] already exists"):
            spawn(1.0, 1.0, 0.0, "turtle1")
        for bad in ("~secret", "has space", "1st", "a//b"):
            with self.assertRaisesRegex(rospy.ServiceException, r"invalid turtle name \[%s\]" % bad):
                spawn(1.0, 1.0, 0.0, bad)
        self.assert_alive_and_finite()

    def test_out_of_range_background_params_are_clamped(self):
        rospy.set_param("/turtlesim/background_r", 999)
        rospy.set_param("/turtlesim/background_g", "green")
        rospy.ServiceProxy("/clear", Empty)()
        self.assertTrue(self.rosout.wait_for_text("~background_g='green' is not a number", level=4))
        rospy.set_param("/turtlesim/background_r", 69)
        rospy.set_param("/turtlesim/background_g", 86)
        self.assert_alive_and_finite()

    def test_set_pen_on_a_killed_turtle_fails(self):
        rospy.ServiceProxy("/spawn", Spawn)(2.0, 2.0, 0.0, "shortlived")
        pen = rospy.ServiceProxy("/shortlived/set_pen", SetPen)
        pen.wait_for_service(5)
        pen(1, 2, 3, 4, 0)
        rospy.ServiceProxy("/kill", Kill)("shortlived")
        with self.assertRaises((rospy.ServiceException, rospy.ROSException)):
            pen(1, 2, 3, 4, 0)
        self.assert_alive_and_finite()


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "turtlesim_errors", TurtlesimErrors)
