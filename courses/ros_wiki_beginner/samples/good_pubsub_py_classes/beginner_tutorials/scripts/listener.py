#!/usr/bin/env python3
import rospy
from std_msgs.msg import String


class Listener:
    def __init__(self):
        self.count = 0
        rospy.Subscriber("/chatter", String, self.on_message, queue_size=5)

    def on_message(self, msg):
        self.count += 1
        print("I heard", msg.data)


if __name__ == "__main__":
    rospy.init_node("listener")
    Listener()
    rospy.spin()
