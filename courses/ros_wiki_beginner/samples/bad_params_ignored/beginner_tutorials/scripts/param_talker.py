#!/usr/bin/env python3
import rospy
from std_msgs.msg import String

rospy.init_node("param_talker")
utterance = rospy.get_param("utterance", "hello world")
pub = rospy.Publisher("chatter", String, queue_size=10)
while not rospy.is_shutdown():
    pub.publish(utterance)
    rospy.sleep(1)
