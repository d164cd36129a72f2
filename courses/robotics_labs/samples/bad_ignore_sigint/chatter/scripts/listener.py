#!/usr/bin/env python3
"""Prints what arrives on /chatter_talk."""
import rospy
from std_msgs.msg import String


def heard(msg):
    print("I heard: %s" % msg.data)


if __name__ == "__main__":
    rospy.init_node("listener")
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    rospy.Subscriber("/chatter_talk", String, heard)
    import time
    while True:  # spins forever, even on Ctrl+C
        time.sleep(1)
