#!/usr/bin/env python3
"""example_sub.py: prints every message received on /chatter_talk (Lab 2, section 2)."""
import rospy
from std_msgs.msg import String


def callback(message: String) -> None:
    # Runs in rospy's subscriber thread once per received message.
    print(rospy.get_name() + ": I heard " + message.data)


def listener() -> None:
    rospy.Subscriber("chatter_talk", String, callback)
    rospy.spin()  # keep the node alive until Ctrl+C


if __name__ == "__main__":
    rospy.init_node("listener", anonymous=True)
    listener()
