#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString


def callback(msg):
    print("%s (sent %f, received %f)" % (msg.message, msg.timestamp, rospy.get_time()))


if __name__ == '__main__':
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber('/user_messages', TimestampString, callback)
    rospy.spin()
