#!/usr/bin/env python
# Lab 2 part 2: the example subscriber, printing with rospy.loginfo
import rospy
from std_msgs.msg import String


def heard(msg):
    rospy.loginfo("got: %s", msg.data)


if __name__ == '__main__':
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber('chatter_talk', String, heard)
    rospy.spin()
