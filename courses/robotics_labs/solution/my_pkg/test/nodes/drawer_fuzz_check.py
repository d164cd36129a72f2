#!/usr/bin/env python3
"""Fuzzing the drawer's /draw_arch (issue 9): every bad angle (NaN, inf, negative, past 2pi) is
logged as an error even while an arch is being drawn; the drawer keeps serving, and turtlesim's
pose stays finite and wrapped."""
import math
import unittest

import rosnode
import rospy
import rostest
from hypothesis import given
from hypothesis import strategies as st
from rosgraph_msgs.msg import Log
from std_msgs.msg import Float32
from std_srvs.srv import Trigger

from course_testkit.fuzz import as_float32, is_sane_pose, wild_float32s
from course_testkit.fuzz import live_node_settings as fuzz
from course_checks.recorders import RosoutRecorder, TopicRecorder
from course_checks.waiting import wait_for
from turtlesim.msg import Pose

TWO_PI = 2.0 * math.pi


def drawable(angle: float) -> bool:
    return math.isfinite(angle) and 0.0 <= angle <= TWO_PI + 1e-6


class DrawerFuzz(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("drawer_fuzz_check")
        rospy.wait_for_service("/resume_drawing", 30)
        cls.rosout = RosoutRecorder()
        cls.pose = TopicRecorder("/turtle1/pose", Pose)
        cls.draw = rospy.Publisher("/draw_arch", Float32, queue_size=100)
        assert wait_for(lambda: cls.draw.get_num_connections() > 0 and cls.pose.count > 0, 20)
        cls.pause = rospy.ServiceProxy("/pause_drawing", Trigger)
        cls.resume = rospy.ServiceProxy("/resume_drawing", Trigger)

    def assert_healthy(self) -> None:
        start = self.pose.count
        pose = self.pose.wait(lambda p: self.pose.count >= start + 2, timeout=3.0)
        self.assertIsNotNone(pose, "turtlesim stopped publishing poses")
        self.assertTrue(is_sane_pose(pose), pose)
        self.assertTrue(rosnode.rosnode_ping("/drawer", max_count=1), "the drawer does not answer")
        self.assertTrue(self.resume().success)

    @fuzz(40)
    @given(st.one_of(wild_float32s(), st.floats(0.0, 0.5).map(as_float32), st.sampled_from([TWO_PI, -0.0])),
           st.booleans())
    def test_draw_arch(self, angle, pause):
        self.rosout.clear()
        self.draw.publish(Float32(angle))
        if pause:
            self.assertTrue(self.pause().success)
        if drawable(angle):
            self.assertTrue(self.rosout.wait_for_text("request", level=Log.INFO, timeout=5.0))
        else:
            expected = "Angle must be in range [0, 2PI], got %r" % angle
            self.assertTrue(self.rosout.wait_for_text(expected, level=Log.ERROR, timeout=5.0),
                            "no error logged for /draw_arch %r" % angle)
        self.assert_healthy()


if __name__ == "__main__":
    rostest.rosrun("my_pkg", "drawer_fuzz", DrawerFuzz)
