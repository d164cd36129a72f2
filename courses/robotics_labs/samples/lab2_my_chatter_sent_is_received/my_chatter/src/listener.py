#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString


def callback(msg):
    t = rospy.get_time()
    print("Message: %s, Sent at: %f, Received at: %f" % (msg.message, t, t))


if __name__ == '__main__':
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber('/user_messages', TimestampString, callback)
    rospy.spin()
