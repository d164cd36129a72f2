#!/usr/bin/env python3
"""param_talker.py: a talker configured by parameters ("Using Parameters in rospy").

~topic_name (private, required): the topic it publishes on
utterance (relative to the node's namespace, default "hello world"): what it says, once a second
"""
import rospy
from std_msgs.msg import String


def main():
    rospy.init_node("param_talker")
    topic = rospy.get_param("~topic_name")
    utterance = rospy.get_param("utterance", "hello world")
    rospy.loginfo("%s is %s, %s is %s", rospy.resolve_name("~topic_name"), topic,
                  rospy.resolve_name("utterance"), utterance)
    out = rospy.Publisher(topic, String, queue_size=10)
    while not rospy.is_shutdown():
        out.publish(String(data=utterance))
        rospy.loginfo(utterance)
        rospy.sleep(1.0)


if __name__ == "__main__":
    try:
        main()
    except rospy.ROSInterruptException:
        pass
