#!/usr/bin/env python3
"""Seed 000: after driving the turtle, pose_subscriber's log shows the new X/Y (from /rosout)."""
import re
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_testkit.nodes import NodeProcess
from course_testkit.recorders import RosoutRecorder, TopicRecorder
from course_testkit.waiting import wait_for

LINE = r"Current Turtle Position - X: ([0-9.]+), Y: ([0-9.]+)"


class PoseSubscriberMilestone(unittest.TestCase):
    def test_logs_moving_position(self):
        log = RosoutRecorder()
        poses = TopicRecorder("/turtle1/pose", Pose)
        node = NodeProcess.rosrun(rospy.get_param("~node_pkg"), rospy.get_param("~node_type"))
        try:
            self.assertTrue(wait_for(lambda: log.matching(LINE), 20), "no position lines on /rosout")
            pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
            twist = Twist()
            twist.linear.x = 2.0

            def moved():
                pub.publish(twist)
                return poses.last and poses.last.x > 7.0
            self.assertTrue(wait_for(moved, 10, interval=0.1))
            pub.publish(Twist())

            def logged_far():
                return [m for m in log.matching(LINE) if float(re.search(LINE, m.msg).group(1)) > 7.0]
            self.assertTrue(wait_for(logged_far, 10), "the log does not follow the turtle")
        finally:
            node.stop()


if __name__ == "__main__":
    rospy.init_node("milestone_pose_subscriber")
    rostest.rosrun("my_robot_controller", "milestone_pose_subscriber", PoseSubscriberMilestone)
