#!/usr/bin/env python3
"""Another student's go to goal, in two phases: first turn in place to face the goal, then drive
straight to it, correcting the heading a little on the way."""
import math
import sys

import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose


class Goal:
    def __init__(self, x, y):
        self.x, self.y = x, y
        self.phase = "turn"
        self.pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose, queue_size=1)

    def on_pose(self, pose):
        dx, dy = self.x - pose.x, self.y - pose.y
        distance = math.hypot(dx, dy)
        error = math.atan2(dy, dx) - pose.theta
        error = math.atan2(math.sin(error), math.cos(error))
        move = Twist()
        if self.phase == "turn":
            move.angular.z = 4.0 * error
            if abs(error) < 0.01:
                self.phase = "drive"
        elif self.phase == "drive":
            if distance < 0.03:
                self.phase = "stop"
            else:
                move.linear.x = min(1.5, 1.2 * distance)
                move.angular.z = 2.0 * error
        elif pose.linear_velocity == 0.0 and pose.angular_velocity == 0.0:
            self.phase = "done"
        if self.pub.get_num_connections() > 0:
            self.pub.publish(move)


def main():
    args = rospy.myargv()
    if len(args) < 3:
        sys.exit("give the goal: X Y")
    rospy.init_node("go_to_goal", anonymous=True)
    goal = Goal(float(args[1]), float(args[2]))
    while not rospy.is_shutdown() and goal.phase != "done":
        rospy.rostime.wallsleep(0.05)


if __name__ == "__main__":
    main()
