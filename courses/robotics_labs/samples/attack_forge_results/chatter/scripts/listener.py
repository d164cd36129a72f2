#!/usr/bin/env python3
"""Subscribes to /chatter_talk but never prints what it hears (the bug)."""
import rospy
from std_msgs.msg import String


def heard(msg):
    pass


if __name__ == "__main__":
    rospy.init_node("listener")
    rospy.Subscriber("/chatter_talk", String, heard)
    rospy.spin()
