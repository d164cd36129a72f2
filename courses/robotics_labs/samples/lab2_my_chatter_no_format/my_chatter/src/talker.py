#!/usr/bin/env python
import sys
import rospy
from my_chatter.msg import TimestampString

rospy.init_node('talker', anonymous=True)
pub = rospy.Publisher('user_messages', TimestampString, queue_size=10)
while not rospy.is_shutdown():
    sys.stdout.write("Please enter a line of text and press <Enter>:\n")
    line = sys.stdin.readline()
    if not line:
        break
    msg = TimestampString()
    msg.message = line.strip()
    msg.timestamp = rospy.get_time()
    pub.publish(msg)
