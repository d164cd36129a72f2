#!/usr/bin/env python3
"""Keyboard teleop: i forward, k backward, j left, l right, space stop, Ctrl-C quit."""
import os
import sys
import termios

import rospy
from geometry_msgs.msg import Twist

BINDINGS = {"i": (1, 0), "k": (-1, 0), "j": (0, 1), "l": (0, -1), " ": (0, 0)}


class Teleop:
    def __init__(self):
        self.linear_scale = rospy.get_param("linear_scale", 1.0)
        self.angular_scale = rospy.get_param("angular_scale", 1.0)
        self.pub = rospy.Publisher(rospy.get_param("cmd_vel_topic_name", "turtle1/cmd_vel"), Twist, queue_size=1)

    def send(self, key):
        lin, ang = BINDINGS[key]
        twist = Twist()
        twist.linear.x = self.linear_scale * lin
        twist.angular.z = self.angular_scale * ang
        self.pub.publish(twist)


def main():
    rospy.init_node("mybot_teleop")
    teleop = Teleop()
    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd)
    mode = termios.tcgetattr(fd)
    mode[3] &= ~(termios.ICANON | termios.ECHO)
    termios.tcsetattr(fd, termios.TCSANOW, mode)
    try:
        while not rospy.is_shutdown():
            key = os.read(fd, 1).decode(errors="ignore")
            if key in BINDINGS:
                teleop.send(key)
            elif key == "\x03":
                break
    finally:
        termios.tcsetattr(fd, termios.TCSANOW, saved)


if __name__ == "__main__":
    main()
