#!/usr/bin/env python3
"""Seed 004 custom interfaces: Person arrives on /person_info; /add_two_ints adds (and refuses an
int32 overflow without dying); the progress action sends rising feedback and the sum 1..num."""
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus

from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for
from pkg_interfaces.msg import Person, ProgressAction, ProgressGoal
from pkg_interfaces.srv import Add


class InterfacesMilestone(unittest.TestCase):
    def test_person_topic(self):
        people = TopicRecorder("/person_info", Person)
        self.assertTrue(wait_for(lambda: people.last, 15), "no Person on /person_info")
        self.assertTrue(people.last.name)

    def test_add_service(self):
        rospy.wait_for_service("/add_two_ints", 20)
        add = rospy.ServiceProxy("/add_two_ints", Add)
        self.assertEqual(add(2, 3).sum, 5)
        self.assertEqual(add(-7, 4).sum, -3)
        with self.assertRaises(rospy.ServiceException):
            add(2 ** 31 - 1, 1)
        self.assertEqual(add(1, 1).sum, 2)

    def test_progress_action(self):
        client = actionlib.SimpleActionClient("progress", ProgressAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(20)))
        feedback = []
        client.send_goal(ProgressGoal(10), feedback_cb=lambda fb: feedback.append(fb.progress))
        self.assertTrue(client.wait_for_result(rospy.Duration(30)))
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED)
        self.assertEqual(client.get_result().sum, 55)
        self.assertGreaterEqual(len(feedback), 3)
        self.assertEqual(feedback, sorted(feedback))
        self.assertAlmostEqual(feedback[-1], 1.0)
        client.send_goal(ProgressGoal(0))
        self.assertTrue(client.wait_for_result(rospy.Duration(10)))
        self.assertEqual(client.get_state(), GoalStatus.ABORTED)


if __name__ == "__main__":
    rospy.init_node("milestone_interfaces")
    rostest.rosrun("pkg_interfaces", "milestone_interfaces", InterfacesMilestone)
