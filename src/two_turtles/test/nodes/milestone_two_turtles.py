#!/usr/bin/env python3
"""Both turtles (turtlesim1/turtle1 and turtlesim2/turtle1) move the same way from one Twist
on /turtle1/cmd_vel, the topic the teleop publishes."""
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for

NAMESPACES = ("/turtlesim1", "/turtlesim2")


class TwoTurtlesMilestone(unittest.TestCase):
    def test_one_command_moves_both(self):
        poses = {ns: TopicRecorder(ns + "/turtle1/pose", Pose) for ns in NAMESPACES}
        self.assertTrue(wait_for(lambda: all(r.last for r in poses.values()), 30), "a turtlesim is missing")
        start = {ns: r.last for ns, r in poses.items()}
        pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        self.assertTrue(wait_for(lambda: pub.get_num_connections() >= 2, 30),
                        "expected two relays subscribed to /turtle1/cmd_vel")
        twist = Twist()
        twist.linear.x, twist.angular.z = 2.0, 1.0

        def both_moved():
            pub.publish(twist)
            return all(abs(poses[ns].last.theta - start[ns].theta) > 0.3 and
                       abs(poses[ns].last.x - start[ns].x) > 0.2 for ns in NAMESPACES)
        self.assertTrue(wait_for(both_moved, 20, interval=0.1), "not both turtles moved")
        a, b = (poses[ns].last for ns in NAMESPACES)
        self.assertAlmostEqual(a.linear_velocity, 2.0, places=3)
        self.assertAlmostEqual(b.linear_velocity, 2.0, places=3)


if __name__ == "__main__":
    rospy.init_node("milestone_two_turtles")
    rostest.rosrun("two_turtles", "milestone_two_turtles", TwoTurtlesMilestone)
