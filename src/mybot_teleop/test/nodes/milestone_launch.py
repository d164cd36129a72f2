#!/usr/bin/env python3
"""Milestones 2.3 (UPMC part 1): `roslaunch mybot_teleop turtlesim.launch` runs turtlesim and
the teleop with linear_scale/angular_scale from the launch file; turtlebot.launch points the
same node at /cmd_vel. Each launch file runs with a pseudo-terminal as its keyboard."""
import shutil
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_testkit.keyboard import PtyKeyboard
from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for


class LaunchMilestone(unittest.TestCase):
    def launch(self, name):
        pkg = rospy.get_param("~launch_pkg")
        return PtyKeyboard([shutil.which("roslaunch"), pkg, name])

    def press_until(self, keyboard, key, recorder, check, tries=30):
        found = keyboard.press_until(key, lambda: [m for m in recorder.messages if check(m)], tries)
        if found:
            return found[-1]
        self.fail("no matching message on %s after key %r" % (recorder.sub.name, key))

    def test_turtlesim_launch(self):
        keyboard = self.launch("turtlesim.launch")
        poses = TopicRecorder("/turtle1/pose", Pose)
        cmds = TopicRecorder("/turtle1/cmd_vel", Twist)
        try:
            self.assertTrue(wait_for(lambda: poses.last, 30), "turtlesim.launch started no turtlesim")
            linear = float(rospy.get_param("/linear_scale"))
            angular = float(rospy.get_param("/angular_scale"))
            up = self.press_until(keyboard, "up", cmds, lambda m: m.linear.x > 0)
            self.assertAlmostEqual(up.linear.x, linear, places=3)
            self.assertTrue(wait_for(lambda: abs(poses.last.linear_velocity - linear) < 1e-3, 5),
                            "the turtle does not move at linear_scale")
            left = self.press_until(keyboard, "left", cmds, lambda m: m.angular.z > 0)
            self.assertAlmostEqual(left.angular.z, angular, places=3)
        finally:
            keyboard.stop()
            poses.unregister()
            cmds.unregister()

    def test_turtlebot_launch(self):
        cmds = TopicRecorder("/cmd_vel", Twist)
        keyboard = self.launch("turtlebot.launch")
        try:
            up = self.press_until(keyboard, "up", cmds, lambda m: m.linear.x > 0)
            self.assertAlmostEqual(up.linear.x, float(rospy.get_param("/linear_scale")), places=3)
            self.assertEqual(rospy.get_param("/cmd_vel_topic_name").lstrip("/"), "cmd_vel")
            self.assertLessEqual(up.linear.x, 0.22, "faster than the TurtleBot3 Burger can go")
            right = self.press_until(keyboard, "right", cmds, lambda m: m.angular.z < 0)
            self.assertGreaterEqual(right.angular.z, -2.84, "faster than the TurtleBot3 Burger can turn")
        finally:
            keyboard.stop()
            cmds.unregister()


if __name__ == "__main__":
    rospy.init_node("milestone_launch")
    rostest.rosrun("mybot_teleop", "milestone_launch", LaunchMilestone)
