#!/usr/bin/env python3
# Part 5: print where the turtle is, every time turtlesim publishes its pose.
import rospy
from turtlesim.msg import Pose


class PoseSubscriberNode:
    def __init__(self):
        self.sub = rospy.Subscriber("/turtle1/pose", Pose, self.pose_callback, queue_size=10)
        print("pose subscriber started")

    def pose_callback(self, msg):
        print("(x=%.3f, y=%.3f)" % (msg.x, msg.y))


if __name__ == "__main__":
    rospy.init_node("pose_subscriber", anonymous=True)
    PoseSubscriberNode()
    rospy.spin()
