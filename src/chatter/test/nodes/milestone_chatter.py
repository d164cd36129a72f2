#!/usr/bin/env python3
"""Lab 2 section 2: messages arrive on /chatter_talk, and the subscriber prints them."""
import os
import tempfile
import unittest

import rospy
import rostest
from std_msgs.msg import String

from course_testkit.nodes import NodeProcess
from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for


class ChatterMilestone(unittest.TestCase):
    def test_pub_and_sub(self):
        heard = TopicRecorder("/chatter_talk", String)
        self.assertTrue(wait_for(lambda: len(heard.messages) >= 3, 20), "nothing on /chatter_talk")
        log = os.path.join(tempfile.mkdtemp(), "sub.log")
        sub = NodeProcess.rosrun(rospy.get_param("~node_pkg"), rospy.get_param("~sub_type"),
                                 ["__name:=listener_under_test"], log_path=log)
        try:
            def printed():
                with open(log, errors="replace") as f:
                    text = f.read()
                return any(m.data in text for m in heard.messages)
            self.assertTrue(wait_for(printed, 20), "the subscriber printed none of the messages")
        finally:
            sub.stop()


if __name__ == "__main__":
    rospy.init_node("milestone_chatter")
    rostest.rosrun("chatter", "milestone_chatter", ChatterMilestone)
