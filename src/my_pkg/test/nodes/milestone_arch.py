#!/usr/bin/env python3
"""Computer Exercise 1, arch drawer: after /draw_arch A the turtle (reset to the centre first)
ends still, heading at A (wrapped into [-pi, pi)); pause_drawing holds it still, resume_drawing
finishes the arch; a request while busy and bad angles (NaN, 7.0) change nothing."""
import math
import unittest

import rospy
import rostest
from std_msgs.msg import Float32
from std_srvs.srv import Trigger
from turtlesim.msg import Pose

from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for

TOLERANCE = 0.06


def wrap(a):
    return a - 2 * math.pi * math.floor((a + math.pi) / (2 * math.pi))


class ArchMilestone(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.poses = TopicRecorder("/turtle1/pose", Pose)
        cls.draw = rospy.Publisher("/draw_arch", Float32, queue_size=10)
        for name in ("/pause_drawing", "/resume_drawing"):
            rospy.wait_for_service(name, 30)
        cls.pause = rospy.ServiceProxy("/pause_drawing", Trigger)
        cls.resume = rospy.ServiceProxy("/resume_drawing", Trigger)
        assert wait_for(lambda: cls.draw.get_num_connections() > 0, 30), "drawer does not subscribe /draw_arch"

    def moving(self):
        p = self.poses.last
        return p is not None and (abs(p.linear_velocity) > 1e-6 or abs(p.angular_velocity) > 1e-6)

    def draw_and_wait(self, angle, timeout=40.0):
        self.draw.publish(Float32(angle))
        self.assertTrue(wait_for(self.moving, 10), "the turtle did not start drawing %.2f" % angle)
        self.assertTrue(wait_for(self.still_for_a_while, timeout), "the turtle did not stop")

    def still_for_a_while(self):
        recent = self.poses.messages[-20:]
        return len(recent) == 20 and all(abs(p.linear_velocity) < 1e-6 and abs(p.angular_velocity) < 1e-6
                                         for p in recent)

    def assert_heading(self, angle):
        theta = self.poses.last.theta
        error = abs(wrap(theta - angle))
        self.assertLess(error, TOLERANCE, "heading %.3f, wanted %.3f" % (theta, wrap(angle)))

    def test_1_arch_reaches_the_angle(self):
        self.draw_and_wait(1.5)
        self.assert_heading(1.5)
        last = self.poses.last
        self.assertGreater(math.hypot(last.x - 5.5444, last.y - 5.5444), 1.0, "no arch was drawn")

    def test_2_pause_resume_and_busy(self):
        self.draw.publish(Float32(4.0))  # beyond pi: ends at 4.0 - 2pi
        self.assertTrue(wait_for(self.moving, 10))
        rospy.sleep(1.0)
        self.draw.publish(Float32(0.5))  # busy: must be ignored
        self.assertTrue(self.pause().success)
        self.assertTrue(wait_for(self.still_for_a_while, 5), "pause_drawing did not stop the turtle")
        held = self.poses.last.theta
        rospy.sleep(1.0)
        self.assertAlmostEqual(self.poses.last.theta, held, places=3, msg="turtle moved while paused")
        self.assertTrue(self.resume().success)
        self.assertTrue(wait_for(self.moving, 5), "resume_drawing did not restart the turtle")
        self.assertTrue(wait_for(self.still_for_a_while, 40))
        self.assert_heading(4.0)

    def test_3_bad_angles_then_a_good_one(self):
        for bad in (float("nan"), 7.0, -1.0):
            self.draw.publish(Float32(bad))
        rospy.sleep(0.5)
        self.assertFalse(self.moving(), "a bad angle made the turtle move")
        self.draw_and_wait(0.8)
        self.assert_heading(0.8)


if __name__ == "__main__":
    rospy.init_node("milestone_arch")
    rostest.rosrun("my_pkg", "milestone_arch", ArchMilestone)
