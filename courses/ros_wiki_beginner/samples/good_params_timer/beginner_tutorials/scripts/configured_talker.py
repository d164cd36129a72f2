#!/usr/bin/env python3
"""Says the `utterance` parameter on the topic the private ~topic_name names, twice a second."""
import rospy
from std_msgs.msg import String


class ConfiguredTalker:
    def __init__(self):
        self.topic = rospy.get_param("~topic_name")
        self.words = rospy.get_param("utterance") if rospy.has_param("utterance") else "hello world"
        self.pub = rospy.Publisher(self.topic, String, queue_size=1)
        self.timer = rospy.Timer(rospy.Duration(0.5), self.say)
        rospy.loginfo("saying %r on %s", self.words, self.pub.resolved_name)

    def say(self, _event):
        self.pub.publish(String(self.words))


if __name__ == "__main__":
    rospy.init_node("param_talker")
    ConfiguredTalker()
    rospy.spin()
