#!/usr/bin/env python3
"""Lab 2 checkpoint 1: the publisher prompts, publishes each typed line with its entry time on
/user_messages, and ends at end of input; the subscriber prints
`Message: <message>, Sent at: <timestamp>, Received at: <timestamp>`."""
import os
import re
import subprocess
import tempfile
import time
import unittest

import rospy
import rostest

from course_testkit.nodes import NodeProcess
from course_testkit.waiting import wait_for
from my_chatter.msg import TimestampString

PROMPT = "Please enter a line of text and press <Enter>:"


class MyChatterMilestone(unittest.TestCase):
    def test_typed_lines_are_published_and_printed(self):
        pkg = rospy.get_param("~node_pkg")
        received = []
        listener = rospy.Subscriber("/user_messages", TimestampString, received.append)
        log_dir = tempfile.mkdtemp()
        sub = NodeProcess.rosrun(pkg, rospy.get_param("~sub_type"), log_path=os.path.join(log_dir, "sub.log"))
        pub = NodeProcess.rosrun(pkg, rospy.get_param("~pub_type"), stdin=subprocess.PIPE,
                                 log_path=os.path.join(log_dir, "pub.log"))
        try:
            self.assertTrue(wait_for(lambda: listener.get_num_connections() > 0, 20),
                            "the publisher never advertised /user_messages")
            # warm-up lines until one arrives: the first publish can race the connection handshake
            for i in range(20):
                pub.proc.stdin.write(b"warm up\n")
                pub.proc.stdin.flush()
                if wait_for(lambda: received, 1.0):
                    break
            self.assertTrue(received, "nothing typed arrived on /user_messages")
            rospy.sleep(0.5)
            del received[:]
            before = time.time()
            lines = ["hello turtle", "second line"]
            for line in lines:
                pub.proc.stdin.write((line + "\n").encode())
                pub.proc.stdin.flush()
                time.sleep(0.3)
            self.assertTrue(wait_for(lambda: len(received) >= 2, 20), "got %d messages" % len(received))
            self.assertEqual([m.message for m in received[:2]], lines)
            self.assertTrue(all(abs(m.timestamp - before) < 30 for m in received[:2]), "timestamp is not the entry time")
            pub.proc.stdin.close()  # end of input: the publisher must exit
            self.assertTrue(wait_for(lambda: not pub.running(), 15), "publisher did not stop at end of input")
            with open(os.path.join(log_dir, "pub.log"), errors="replace") as f:
                self.assertIn(PROMPT, f.read())
            pattern = r"Message: hello turtle, Sent at: [0-9.e+]+, Received at: [0-9.e+]+"

            def printed():
                with open(os.path.join(log_dir, "sub.log"), errors="replace") as f:
                    return re.search(pattern, f.read())
            self.assertTrue(wait_for(printed, 10), "subscriber output does not match the format")
        finally:
            pub.stop()
            sub.stop()


if __name__ == "__main__":
    rospy.init_node("milestone_my_chatter")
    rostest.rosrun("my_chatter", "milestone_my_chatter", MyChatterMilestone)
