#!/usr/bin/env python3
"""Milestone `tf2_static` (004 10, section 4): `rosrun tf2_ros static_transform_publisher 0 0 3 0 0 3.14 A B`
(4.1) publishes a fixed frame B 3 m above A, turned 3.14 rad (ROS 1 argument order: x y z yaw pitch
roll), and `tf2_echo A B` (4.2) shows it: Debian has no tf2_ros tf2_echo, so both the course's
`rosrun turtle_tf2 tf2_echo` and Debian's `rosrun tf2_tools echo.py` are checked.

This milestone checks the course workspace (tf2 and the echo tools), not a student package.
"""
import math
import subprocess

import rospy
import rostest
import tf2_ros

from course_rospy import quick_exit
from course_format import causes
from course_milestones.milestone_case import MilestoneCase

from turtle_tf2.geometry import euler_from_quaternion


class StaticTransformTest(MilestoneCase):
    failure_cause = "course_tools"  # the course's own tools: unittest's words, this cause

    @classmethod
    def setUpClass(cls):
        quick_exit.install()  # before init_node: rospy's exit without a spinning core
        rospy.init_node("tf2_static_check")

    def test_lookup_a_to_b(self):
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        seen = buffer.lookup_transform("A", "B", rospy.Time(0), rospy.Duration(15.0))
        t, q = seen.transform.translation, seen.transform.rotation
        self.assertEqual((t.x, t.y, t.z), (0.0, 0.0, 3.0))
        roll, pitch, yaw = euler_from_quaternion((q.x, q.y, q.z, q.w))
        self.assertAlmostEqual(roll, 3.14, places=5)
        self.assertAlmostEqual(pitch, 0.0, places=5)
        self.assertAlmostEqual(yaw, 0.0, places=5)

    def test_our_tf2_echo(self):
        out = subprocess.run(["rosrun", "turtle_tf2", "tf2_echo", "A", "B", "--limit", "1", "--timeout", "20"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=40)
        self.assertEqual(out.returncode, 0, causes.finding("course_tools", out.stderr))
        self.assertIn("- Translation: [0.000, 0.000, 3.000]", out.stdout)
        self.assertIn("- Rotation: in RPY (radian) [3.140, 0.000, 0.000]", out.stdout)

    def test_our_tf2_echo_times_out_on_an_unknown_frame(self):
        out = subprocess.run(["rosrun", "turtle_tf2", "tf2_echo", "A", "nowhere", "--limit", "1", "--timeout", "2"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=40)
        self.assertEqual(out.returncode, 1)
        self.assertIn("no transform A -> nowhere", out.stderr)

    def test_debian_tf2_tools_echo(self):
        out = subprocess.run(["rosrun", "tf2_tools", "echo.py", "A", "B", "--limit", "1"],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=40)
        self.assertEqual(out.returncode, 0, causes.finding("course_tools", out.stdout))
        self.assertIn("- Translation: [0.000, 0.000, 3.000]", out.stdout)


if __name__ == "__main__":
    rostest.rosrun("course_milestones", "tf2_static", StaticTransformTest)
