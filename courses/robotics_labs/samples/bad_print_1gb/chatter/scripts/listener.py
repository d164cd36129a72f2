#!/usr/bin/env python3
"""Prints what arrives on /chatter_talk."""
import rospy
from std_msgs.msg import String


def heard(msg):
    print("I heard: %s" % msg.data)


if __name__ == "__main__":
    import sys
    for _ in range(1024):  # a debug dump of 1 GB
        sys.stdout.write("debug " * 174763 + "\n")
    rospy.init_node("listener")
    rospy.Subscriber("/chatter_talk", String, heard)
    rospy.spin()
