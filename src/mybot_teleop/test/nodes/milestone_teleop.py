#!/usr/bin/env python3
"""Milestone 2.1 (UPMC part 1): arrow keys typed into the node's terminal become Twists
on /turtle1/cmd_vel and move the turtle; q quits and gives the terminal back; without a
terminal the node refuses with a clear message."""
import subprocess
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_testkit.keyboard import PtyKeyboard
from course_testkit.nodes import find_executable
from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for


class TeleopMilestone(unittest.TestCase):
    def setUp(self):
        self.pkg = rospy.get_param("~node_pkg")
        self.type = rospy.get_param("~node_type")
        self.cmds = TopicRecorder("/turtle1/cmd_vel", Twist)
        self.poses = TopicRecorder("/turtle1/pose", Pose)
        self.assertTrue(wait_for(lambda: self.poses.last, 20), "turtlesim publishes no pose")
        self.keyboard = PtyKeyboard.rosrun(self.pkg, self.type)

    def tearDown(self):
        self.keyboard.stop()
        self.cmds.unregister()
        self.poses.unregister()

    def press_until_command(self, key, check):
        """Press a key (again every second, as the node may still be starting) until a
        command satisfying check() arrives; return it."""
        self.cmds.clear()
        found = self.keyboard.press_until(key, lambda: [m for m in self.cmds.messages if check(m)])
        if found:
            return found[-1]
        self.fail("no command for key %r on /turtle1/cmd_vel" % key)

    def test_arrows_drive_the_turtle_and_q_quits(self):
        start = self.poses.last
        up = self.press_until_command("up", lambda m: m.linear.x > 0)
        self.assertAlmostEqual(up.angular.z, 0.0)
        # turtlesim's connection to the new node may come up after ours: press until the turtle moves
        self.assertTrue(self.keyboard.press_until("up", lambda: self.poses.last.x > start.x + 0.2, tries=10,
                                                  interval=1.5), "the turtle did not move forward after the up arrow")
        down = self.press_until_command("down", lambda m: m.linear.x < 0)
        self.assertAlmostEqual(down.linear.x, -up.linear.x, places=3)
        left = self.press_until_command("left", lambda m: m.angular.z > 0)
        self.assertAlmostEqual(left.linear.x, 0.0)
        right = self.press_until_command("right", lambda m: m.angular.z < 0)
        self.assertAlmostEqual(right.angular.z, -left.angular.z, places=3)
        self.keyboard.press("q")
        self.assertTrue(wait_for(lambda: not self.keyboard.node.running(), 10), "q did not quit the node")
        self.assertTrue(self.keyboard.terminal_settings_echo(), "the terminal was not restored (echo off)")

    def test_without_a_terminal_the_node_says_so(self):
        proc = subprocess.run([find_executable(self.pkg, self.type), "__name:=teleop_no_tty"],
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=30)
        self.assertNotEqual(proc.returncode, 0, "the node should fail without a terminal")
        self.assertRegex(proc.stdout.decode(errors="replace").lower(), r"terminal|tty")


if __name__ == "__main__":
    rospy.init_node("milestone_teleop")
    rostest.rosrun("mybot_teleop", "milestone_teleop", TeleopMilestone)
