#!/usr/bin/env python3
"""drive_straight.py DISTANCE: drives turtle1 DISTANCE m straight ahead (backwards when negative),
then stops it and exits. The distance is measured on turtle1's pose, and the speed falls as the
end comes near, so that the turtle stops where it should."""
import math
import sys

import rospy
from geometry_msgs.msg import Twist, Vector3
from turtlesim.msg import Pose

TOP_SPEED = 1.0    # m/s
LEAST_SPEED = 0.05
GAIN = 2.0         # 1/s: speed per metre still to go
CLOSE = 0.005      # m


class Driver:
    def __init__(self, distance):
        self.distance = distance
        self.start = None
        self.pose = None
        self.cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=10)
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose)

    def on_pose(self, pose):
        if self.start is None:
            self.start = pose
        self.pose = pose

    def left_to_go(self):
        travelled = math.hypot(self.pose.x - self.start.x, self.pose.y - self.start.y)
        return abs(self.distance) - travelled

    def run(self):
        rate = rospy.Rate(50)
        while not rospy.is_shutdown() and (self.pose is None or self.cmd.get_num_connections() == 0):
            rate.sleep()
        while not rospy.is_shutdown() and self.left_to_go() > CLOSE:
            speed = min(TOP_SPEED, max(LEAST_SPEED, GAIN * self.left_to_go()))
            self.cmd.publish(Twist(linear=Vector3(x=math.copysign(speed, self.distance))))
            rate.sleep()
        while not rospy.is_shutdown() and (self.pose.linear_velocity != 0.0 or self.pose.angular_velocity != 0.0):
            self.cmd.publish(Twist())  # until turtlesim says it stands still
            rate.sleep()


def main():
    args = rospy.myargv()
    if len(args) != 2:
        sys.exit("usage: rosrun turtle_motions drive_straight.py DISTANCE")
    rospy.init_node("drive_straight")
    Driver(float(args[1])).run()


if __name__ == "__main__":
    main()
