#!/usr/bin/env python3
import rospy
from std_msgs.msg import String

rospy.init_node("talker", anonymous=True)
pub = rospy.Publisher("chatter_topic", String, queue_size=10)
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    text = "hello world %s" % rospy.get_time()
    rospy.loginfo(text)
    pub.publish(text)
    rate.sleep()
