#!/usr/bin/env python3
"""Another student's turn in place: the heading is unwrapped into a running angle as poses come,
and the turn rate is proportional to what is left, in the pose callback."""
import math
import sys

import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose


class Turn:
    def __init__(self, angle):
        self.angle = angle
        self.unwrapped = None
        self.start = None
        self.last = None
        self.done = False
        self.pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose, queue_size=1)

    def on_pose(self, pose):
        if self.last is None:
            self.unwrapped = self.start = pose.theta
        else:
            step = pose.theta - self.last
            step -= 2 * math.pi * round(step / (2 * math.pi))
            self.unwrapped += step
        self.last = pose.theta
        left = self.angle - (self.unwrapped - self.start)
        move = Twist()
        if abs(left) > 0.002:
            move.angular.z = max(-1.0, min(1.0, 2.5 * left))
        elif pose.angular_velocity == 0.0:
            self.done = True
        if self.pub.get_num_connections() > 0:
            self.pub.publish(move)


def main():
    if len(rospy.myargv()) < 2:
        sys.exit("give the angle in radians")
    rospy.init_node("turn_in_place", anonymous=True)
    turn = Turn(float(rospy.myargv()[1]))
    while not rospy.is_shutdown() and not turn.done:
        rospy.rostime.wallsleep(0.05)


if __name__ == "__main__":
    main()
