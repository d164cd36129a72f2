#!/usr/bin/env python3
"""rotate.py ANGLE: turns turtle1 in place by ANGLE rad (left when positive, right when negative;
more than a half turn too), then stops it and exits. The angle turned is summed from turtle1's
pose, one heading change at a time, so that a turn past pi counts."""
import math
import sys

import rospy
from geometry_msgs.msg import Twist, Vector3
from turtlesim.msg import Pose

TOP_RATE = 1.5     # rad/s
LEAST_RATE = 0.05
GAIN = 2.0         # 1/s
CLOSE = 0.002      # rad


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


class Rotator:
    def __init__(self, angle):
        self.angle = angle
        self.turned = 0.0
        self.theta = None
        self.pose = None
        self.cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=10)
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose)

    def on_pose(self, pose):
        if self.theta is not None:
            self.turned += wrap(pose.theta - self.theta)
        self.theta = pose.theta
        self.pose = pose

    def run(self):
        rate = rospy.Rate(50)
        while not rospy.is_shutdown() and (self.pose is None or self.cmd.get_num_connections() == 0):
            rate.sleep()
        while not rospy.is_shutdown() and abs(self.angle - self.turned) > CLOSE:
            left = self.angle - self.turned
            turn_rate = min(TOP_RATE, max(LEAST_RATE, GAIN * abs(left)))
            self.cmd.publish(Twist(angular=Vector3(z=math.copysign(turn_rate, left))))
            rate.sleep()
        while not rospy.is_shutdown() and (self.pose.linear_velocity != 0.0 or self.pose.angular_velocity != 0.0):
            self.cmd.publish(Twist())
            rate.sleep()


def main():
    args = rospy.myargv()
    if len(args) != 2:
        sys.exit("usage: rosrun turtle_motions rotate.py ANGLE")
    rospy.init_node("rotate")
    Rotator(float(args[1])).run()


if __name__ == "__main__":
    main()
