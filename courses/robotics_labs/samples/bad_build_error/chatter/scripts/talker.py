#!/usr/bin/env python3
"""Publishes a greeting on /chatter_talk twice a second."""
import rospy
from std_msgs.msg import String

if __name__ == "__main__":
    rospy.init_node("talker")
    pub = rospy.Publisher("/chatter_talk", String, queue_size=10)
    rate = rospy.Rate(2)
    n = 0
    while not rospy.is_shutdown():
        n += 1
        pub.publish(String("hello %d" % n))
        rate.sleep()
