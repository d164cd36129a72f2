#!/usr/bin/env python3
"""Prints what arrives on /chatter_talk."""
import rospy
from std_msgs.msg import String


def heard(msg):
    print("I heard: %s" % msg.data)


if __name__ == "__main__":
    rospy.init_node("listener")
    rospy.Subscriber("/chatter_talk", String, heard)
    rospy.spin()
