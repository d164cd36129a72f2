#!/usr/bin/env python3
# Pen turns red close to a corner of the turtlesim window (within 1.5 m of the corner point)
import math
import rospy
from turtlesim.msg import Pose
from turtlesim.srv import SetPen

SIZE = 11.09
CORNERS = [(0, 0), (SIZE, 0), (0, SIZE), (SIZE, SIZE)]


class PenColor(object):
    def __init__(self):
        rospy.wait_for_service("/turtle1/set_pen")
        self.set_pen = rospy.ServiceProxy("/turtle1/set_pen", SetPen)
        self.red = False
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose)

    def on_pose(self, pose):
        print("x=%.2f y=%.2f" % (pose.x, pose.y))
        near = min(math.hypot(pose.x - cx, pose.y - cy) for cx, cy in CORNERS) < 1.5
        if near and not self.red:
            self.set_pen(255, 0, 0, 3, 0)
        elif self.red and not near:
            self.set_pen(179, 184, 255, 3, 0)
        self.red = near


if __name__ == "__main__":
    rospy.init_node("mybot_color")
    PenColor()
    rospy.spin()
