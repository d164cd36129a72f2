#!/usr/bin/env python3
"""Another student's straight line: all the work in the pose callback, which drives at a speed
that falls with the distance left, measured along the heading the turtle started with, and exits
once turtle1 stands still where it should."""
import math
import sys

import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose


def main():
    if len(rospy.myargv()) < 2:
        sys.exit("give the distance in metres")
    goal = float(rospy.myargv()[1])
    rospy.init_node("straight_line", anonymous=True)
    pub = rospy.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
    state = {"start": None, "done": False}

    def on_pose(pose):
        if state["start"] is None:
            state["start"] = pose
        start = state["start"]
        along = (pose.x - start.x) * math.cos(start.theta) + (pose.y - start.y) * math.sin(start.theta)
        left = goal - along
        move = Twist()
        if abs(left) > 0.003:
            move.linear.x = max(-0.8, min(0.8, 3.0 * left))
        elif pose.linear_velocity == 0.0:
            state["done"] = True
        if pub.get_num_connections() > 0:
            pub.publish(move)

    rospy.Subscriber("turtle1/pose", Pose, on_pose, queue_size=1)
    while not rospy.is_shutdown() and not state["done"]:
        rospy.rostime.wallsleep(0.05)


if __name__ == "__main__":
    main()
