#!/usr/bin/env python3
"""The relay latches its output when its input is latched, as topic_tools relay does, so a
one-shot message (`rostopic pub -1`, or a latched publisher that spoke before the relay started)
reaches every subscriber of OUT, also one that connects later; an unlatched input stays unlatched."""
import os
import subprocess
import tempfile
import unittest

import rosgraph
import rospy
import rostest
from std_msgs.msg import String

from course_checks.nodes import NodeProcess
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

TIMEOUT_S = 20


def subscriber_count(topic: str) -> int:
    state = rosgraph.Master(rospy.get_name()).getSystemState()
    return len(dict(state[1]).get(topic, []))


def received(recorder: TopicRecorder, data: str) -> bool:
    return any(m.data == data for m in recorder.messages)


class RelayLatching(unittest.TestCase):
    def test_one_shot_rostopic_pub_reaches_now_and_later(self):
        """The issue's case: `rostopic pub -1 /a std_msgs/String "data: once"`, /b must get it."""
        self.assertTrue(wait_for(lambda: subscriber_count("/latch_a") >= 2, TIMEOUT_S),
                        "the relays do not subscribe /latch_a")
        now, now_ref = TopicRecorder("/latch_b", String), TopicRecorder("/latch_b_ref", String)
        one_shot = subprocess.run(["rostopic", "pub", "-1", "/latch_a", "std_msgs/String", "data: once"],
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=30)
        self.assertEqual(one_shot.returncode, 0, one_shot.stdout)
        self.assertTrue(wait_for(lambda: received(now_ref, "once"), TIMEOUT_S),
                        "topic_tools relay did not pass the one-shot message (the test is wrong)")
        self.assertTrue(wait_for(lambda: received(now, "once"), TIMEOUT_S),
                        "the one-shot message on /latch_a never reached /latch_b")
        now.unregister()  # the next subscriber gets a connection of its own
        later = TopicRecorder("/latch_b", String)
        self.assertTrue(wait_for(lambda: received(later, "once"), TIMEOUT_S),
                        "a subscriber connecting to /latch_b after the message did not get it (not latched)")
        self.assertEqual(later.messages[0]._connection_header.get("latching"), "1")

    def test_latched_before_the_relay_started(self):
        """A latched publisher that published before the relay existed: OUT gets it; and the relay
        prints no warning on its first message (rospy's SyntaxWarning about queue_size)."""
        log_path = os.path.join(tempfile.mkdtemp(), "relay_early.log")
        pub = rospy.Publisher("/early_a", String, queue_size=1, latch=True)
        pub.publish(String("early"))
        out = TopicRecorder("/early_b", String)
        relay = NodeProcess.rosrun(rospy.get_param("~relay_pkg"), rospy.get_param("~relay_type"),
                                   ["/early_a", "/early_b", "__name:=relay_early"], log_path=log_path)
        try:
            self.assertTrue(wait_for(lambda: received(out, "early"), TIMEOUT_S),
                            "the latched message published before the relay started never reached /early_b")
            self.assertNotIn("Warning", relay.output())
        finally:
            relay.stop()
            pub.unregister()

    def test_unlatched_input_gives_unlatched_output(self):
        pub = rospy.Publisher("/plain_a", String, queue_size=10)
        out = TopicRecorder("/plain_b", String)
        self.assertTrue(wait_for(lambda: pub.publish(String("plain")) or received(out, "plain"), TIMEOUT_S),
                        "nothing relayed from /plain_a to /plain_b")
        self.assertEqual(out.messages[0]._connection_header.get("latching"), "0")


if __name__ == "__main__":
    rospy.init_node("relay_latching")
    rostest.rosrun("course_relay", "relay_latching", RelayLatching)
