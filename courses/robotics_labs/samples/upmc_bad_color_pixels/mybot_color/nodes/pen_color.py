#!/usr/bin/env python3
"""Red pen in the corners of the 500x500 turtlesim window."""
import rospy
from turtlesim.msg import Pose
from turtlesim.srv import SetPen

WINDOW = 500   # pixels
MARGIN = 80    # pixels from the border


class ColorNode:
    def __init__(self):
        rospy.wait_for_service('/turtle1/set_pen')
        self.pen = rospy.ServiceProxy('/turtle1/set_pen', SetPen)
        self.red = None
        rospy.Subscriber('/turtle1/pose', Pose, self.callback)

    def near(self, v):
        return v < MARGIN or v > WINDOW - MARGIN

    def callback(self, pose):
        red = self.near(pose.x) and self.near(pose.y)
        if red != self.red:
            if red:
                self.pen(255, 0, 0, 3, 0)
            else:
                self.pen(179, 184, 255, 3, 0)
            self.red = red


if __name__ == '__main__':
    rospy.init_node('mybot_color')
    ColorNode()
    rospy.spin()
