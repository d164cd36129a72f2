#!/usr/bin/env python3
"""draw_square visits the corners of a 2 m square; mimic copies one turtle's motion to another."""
import math
import subprocess
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty

from turtlesim.constants import CENTRE
from turtlesim.msg import Pose
from turtlesim.srv import Spawn
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for


class Tools(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("tools_check")
        rospy.wait_for_service("/spawn", 20)

    def run_node(self, *argv):
        proc = subprocess.Popen(["rosrun", "turtlesim"] + list(argv))
        self.addCleanup(lambda: (proc.terminate(), proc.wait(10)))
        return proc

    def test_draw_square_reaches_three_corners(self):
        pose = TopicRecorder("/turtle1/pose", Pose)
        self.run_node("draw_square")
        corners = [(CENTRE + 2.0, CENTRE), (CENTRE + 2.0, CENTRE + 2.0), (CENTRE, CENTRE + 2.0)]
        for cx, cy in corners:
            self.assertIsNotNone(pose.wait(lambda p: math.hypot(p.x - cx, p.y - cy) < 0.05, timeout=20),
                                 "corner (%.2f, %.2f) not reached" % (cx, cy))
        pose.unregister()

    def test_mimic_copies_velocity(self):
        rospy.ServiceProxy("/reset", Empty)()
        rospy.ServiceProxy("/spawn", Spawn)(2.0, 2.0, 0.0, "turtle2")
        self.run_node("mimic", "input:=turtle1", "output:=turtle2")
        follower = TopicRecorder("/turtle2/pose", Pose)
        cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        self.assertTrue(wait_for(lambda: cmd.get_num_connections() > 0, 10))
        twist = Twist()
        twist.linear.x, twist.angular.z = 1.5, 0.5

        def moving(p):
            cmd.publish(twist)
            return abs(p.linear_velocity - 1.5) < 1e-4 and abs(p.angular_velocity - 0.5) < 1e-4

        self.assertIsNotNone(follower.wait(moving, timeout=15))
        follower.unregister()


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "turtlesim_tools", Tools)
