#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString


def callback(data):
    now = rospy.get_rostime().to_sec()
    rospy.loginfo("Message: %s, Sent at: %.4f, Received at: %.4f", data.s, data.f, now)


if __name__ == '__main__':
    rospy.init_node('timestamp_listener')
    rospy.Subscriber('/user_messages', TimestampString, callback)
    rospy.spin()
