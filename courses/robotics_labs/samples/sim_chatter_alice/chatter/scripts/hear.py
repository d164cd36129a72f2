#!/usr/bin/env python3
"""Lab 2, section 2: the listener. Prints each greeting heard on /chatter_talk with how long it
took to arrive, and a count every tenth message."""
import sys

import rospy
from std_msgs.msg import String


class Listener:
    def __init__(self):
        self.heard = 0
        self.first = None
        self.subscriber = rospy.Subscriber("/chatter_talk", String, self.on_message, queue_size=20)

    def on_message(self, msg):
        now = rospy.get_time()
        if self.first is None:
            self.first = now
        self.heard += 1
        sys.stdout.write("[%s] heard: %s\n" % (rospy.get_name(), msg.data))
        sys.stdout.flush()
        if self.heard % 10 == 0:
            rate = self.heard / max(now - self.first, 1e-6)
            sys.stdout.write("  %d messages so far, %.1f per second\n" % (self.heard, rate))


if __name__ == "__main__":
    rospy.init_node("alice_listener", anonymous=True)
    Listener()
    rospy.spin()
