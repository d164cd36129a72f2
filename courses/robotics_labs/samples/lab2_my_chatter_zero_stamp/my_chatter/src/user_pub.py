#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString

if __name__ == '__main__':
    rospy.init_node('user_pub', anonymous=True)
    pub = rospy.Publisher('/user_messages', TimestampString, queue_size=10)
    while not rospy.is_shutdown():
        text = input("Please enter a line of text and press <Enter>:\n")
        pub.publish(TimestampString(input=text))
