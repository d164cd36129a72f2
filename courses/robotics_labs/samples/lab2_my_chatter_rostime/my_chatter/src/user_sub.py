#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString


def cb(m):
    print("Message: %s, Sent at: %s, Received at: %s" % (m.message, m.stamp, rospy.Time.now()))


rospy.init_node('user_sub', anonymous=True)
rospy.Subscriber('/user_messages', TimestampString, cb)
rospy.spin()
