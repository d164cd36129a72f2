#!/usr/bin/env python3
"""Fuzzing /turtle1/patrol (issue 9): wild vel, omega and pose; the server refuses what no tick can
draw, turtlesim never gets a number that breaks it, and both nodes keep answering."""
import math
import unittest

import rosnode
import rospy
import rostest
from hypothesis import given
from hypothesis import strategies as st

from course_testkit.fuzz import as_float32, is_sane_pose, wild_float32s
from course_testkit.fuzz import live_node_settings as fuzz
from course_checks.recorders import TopicRecorder
from turtle_patrol.srv import Patrol
from turtlesim.constants import TICK, WORLD_SIZE
from turtlesim.msg import Pose

REFUSALS = ("must be finite", "too fast", "inside the canvas")


def wild_or_within(low: float, high: float):
    """Wild float32 values half the time, servable ones the other half."""
    return st.one_of(wild_float32s(), st.floats(low, high).map(as_float32))


class PatrolFuzz(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("patrol_fuzz_check")
        rospy.wait_for_service("/turtle1/patrol", 30)
        cls.patrol = rospy.ServiceProxy("/turtle1/patrol", Patrol)
        cls.pose = TopicRecorder("/turtle1/pose", Pose)

    def assert_healthy(self, condition=lambda p: True) -> None:
        start = self.pose.count
        pose = self.pose.wait(lambda p: self.pose.count >= start + 3 and condition(p), timeout=3.0)
        self.assertIsNotNone(pose, "no fitting fresh pose from turtlesim (last %s)" % self.pose.last)
        self.assertTrue(is_sane_pose(pose), "pose not finite or theta not wrapped: %s" % pose)
        for node in ("/patrol_server", "/turtlesim"):
            self.assertTrue(rosnode.rosnode_ping(node, max_count=1), "%s does not answer" % node)
        rospy.wait_for_service("/turtle1/patrol", 5)

    served = 0

    @classmethod
    def tearDownClass(cls):
        rospy.loginfo("patrol fuzz: %d requests served" % cls.served)

    @fuzz(40)
    @given(wild_or_within(-700, 700), wild_or_within(-200, 200), wild_or_within(0, WORLD_SIZE),
           wild_or_within(0, WORLD_SIZE), wild_float32s())
    def test_patrol(self, vel, omega, x, y, theta):
        try:
            cmd = self.patrol(vel, omega, x, y, theta).cmd
        except rospy.ServiceException as err:
            self.assertTrue(any(r in str(err) for r in REFUSALS), "unclear refusal: %s" % err)
            self.assert_healthy()
            return
        type(self).served += 1
        self.assertTrue(all(math.isfinite(v) for v in (vel, omega, x, y, theta)))
        self.assertLessEqual(abs(vel) * TICK, WORLD_SIZE + 1e-3)
        self.assertLessEqual(abs(omega) * TICK, math.pi + 1e-3)
        self.assertEqual((cmd.linear.x, cmd.angular.z), (vel, omega))
        want = as_float32(omega)
        self.assert_healthy(lambda p: p.angular_velocity == want)


if __name__ == "__main__":
    rostest.rosrun("turtle_patrol", "patrol_fuzz", PatrolFuzz)
