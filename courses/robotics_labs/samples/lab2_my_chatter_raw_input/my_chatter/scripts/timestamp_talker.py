#!/usr/bin/env python
from __future__ import print_function
import rospy
from my_chatter.msg import TimestampString

try:
    raw_input
except NameError:  # python 3
    raw_input = input


def talker():
    pub = rospy.Publisher('/user_messages', TimestampString, queue_size=10)
    rospy.init_node('timestamp_talker')
    while not rospy.is_shutdown():
        print("Please enter a line of text and press <Enter>:")
        text = raw_input()
        pub.publish(TimestampString(rospy.Time.now().to_sec(), text))


if __name__ == '__main__':
    try:
        talker()
    except (rospy.ROSInterruptException, EOFError, KeyboardInterrupt):
        pass
