#!/usr/bin/env python3
"""What a relay must do: every message on IN arrives unchanged, in order, on OUT, with OUT's
type the input's type (Twist and String here), and OUT defaults to IN_relay."""
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
from std_msgs.msg import String

from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for


class RelayBehaviour(unittest.TestCase):
    def relay_through(self, in_topic, out_topic, msg_type, make, count=50):
        out = TopicRecorder(out_topic, msg_type)
        pub = rospy.Publisher(in_topic, msg_type, queue_size=count)
        # the relay advertises OUT after its first message: send probes until one comes through
        probe = make(-1)
        self.assertTrue(wait_for(lambda: pub.get_num_connections() > 0, 20), "relay does not subscribe " + in_topic)
        for _ in range(100):
            pub.publish(probe)
            if wait_for(lambda: out.messages, 0.2):
                break
        self.assertTrue(out.messages, "nothing relayed from %s to %s" % (in_topic, out_topic))
        self.assertTrue(wait_for(lambda: out.sub.get_num_connections() > 0, 10))
        out.clear()
        sent = [make(i) for i in range(count)]
        for m in sent:
            pub.publish(m)
            rospy.sleep(0.005)
        self.assertTrue(wait_for(lambda: len(out.messages) >= count, 10),
                        "%d of %d relayed" % (len(out.messages), count))
        self.assertEqual(out.messages, sent)
        types = dict(rospy.get_published_topics())
        self.assertEqual(types.get(out_topic), msg_type._type)

    def test_twist_to_named_output(self):
        def twist(i):
            t = Twist()
            t.linear.x, t.angular.z = i * 0.5, -i
            return t
        self.relay_through("/relay_in", "/relay_out", Twist, twist)

    def test_default_output_is_in_relay(self):
        self.relay_through("/words", "/words_relay", String, lambda i: String("word %d" % i))

    def test_lazy_relay_listens_only_while_someone_listens(self):
        """~lazy: with no subscriber on OUT the relay drops its IN subscription, and takes it back."""
        master = rosgraph.Master("/relay_behaviour")

        def relay_subscribes_input() -> bool:
            return "/relay_lazy" in dict(master.getSystemState()[1]).get("/lazy_in", [])

        pub = rospy.Publisher("/lazy_in", String, queue_size=10)
        out = TopicRecorder("/lazy_out", String)
        self.assertTrue(wait_for(lambda: pub.get_num_connections() > 0, 20))
        self.assertTrue(wait_for(lambda: pub.publish(String("probe")) or out.messages, 20), "nothing relayed")
        out.unregister()
        # topic_tools drops IN when a message arrives and OUT has no subscriber: keep messages coming
        self.assertTrue(wait_for(lambda: pub.publish(String("unheard")) or not relay_subscribes_input(), 20),
                        "the lazy relay still subscribes /lazy_in with nobody on /lazy_out")
        back = TopicRecorder("/lazy_out", String)
        self.assertTrue(wait_for(relay_subscribes_input, 20), "the lazy relay did not subscribe /lazy_in again")
        self.assertTrue(wait_for(lambda: pub.publish(String("heard")) or
                                 any(m.data == "heard" for m in back.messages), 20))
        back.unregister()


if __name__ == "__main__":
    rospy.init_node("relay_behaviour")
    rostest.rosrun("course_relay", "relay_behaviour", RelayBehaviour)
