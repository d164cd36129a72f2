#!/usr/bin/env python3
import rospy
from std_msgs.msg import String


def main():
    rospy.init_node("param_talker")
    topic_name = rospy.get_param("~topic_name")
    utterance = rospy.get_param("~utterance", "hello world")
    pub = rospy.Publisher(topic_name, String, queue_size=10)
    while not rospy.is_shutdown():
        rospy.loginfo(utterance)
        pub.publish(utterance)
        rospy.sleep(1)


if __name__ == "__main__":
    main()
