#!/usr/bin/env python3
"""go_to_goal.py X Y: drives turtle1 to the point (X, Y) of turtlesim's canvas and stops it within
5 cm of it, then exits: it steers towards the goal while it drives, slower as it comes near."""
import math
import sys

import rospy
from geometry_msgs.msg import Twist, Vector3
from turtlesim.msg import Pose

TOP_SPEED = 2.0    # m/s
LINEAR_GAIN = 1.5  # 1/s
ANGULAR_GAIN = 6.0
FACING = 0.3       # rad: drive only when the goal is this close to straight ahead
CLOSE = 0.02       # m


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


class GoalDriver:
    def __init__(self, x, y):
        self.goal = (x, y)
        self.pose = None
        self.cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=10)
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose)

    def on_pose(self, pose):
        self.pose = pose

    def distance(self):
        return math.hypot(self.goal[0] - self.pose.x, self.goal[1] - self.pose.y)

    def run(self):
        rate = rospy.Rate(50)
        while not rospy.is_shutdown() and (self.pose is None or self.cmd.get_num_connections() == 0):
            rate.sleep()
        while not rospy.is_shutdown() and self.distance() > CLOSE:
            bearing = math.atan2(self.goal[1] - self.pose.y, self.goal[0] - self.pose.x)
            off = wrap(bearing - self.pose.theta)
            speed = min(TOP_SPEED, LINEAR_GAIN * self.distance()) if abs(off) < FACING else 0.0
            self.cmd.publish(Twist(linear=Vector3(x=speed), angular=Vector3(z=ANGULAR_GAIN * off)))
            rate.sleep()
        while not rospy.is_shutdown() and (self.pose.linear_velocity != 0.0 or self.pose.angular_velocity != 0.0):
            self.cmd.publish(Twist())
            rate.sleep()


def main():
    args = rospy.myargv()
    if len(args) != 3:
        sys.exit("usage: rosrun turtle_motions go_to_goal.py X Y")
    rospy.init_node("go_to_goal")
    GoalDriver(float(args[1]), float(args[2])).run()


if __name__ == "__main__":
    main()
