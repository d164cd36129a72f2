#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString


def callback(msg):
    print("Message: " + msg.input + ", Sent at: " + str(msg.time) + ", Received at: " + str(rospy.get_time()))


def listener():
    rospy.init_node('user_listener', anonymous=True)
    rospy.Subscriber('user_messages', TimestampString, callback)
    rospy.spin()


if __name__ == '__main__':
    listener()
