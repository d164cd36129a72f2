#!/usr/bin/env python3
import sys
import tty
import termios

import rospy
from geometry_msgs.msg import Twist


def get_key():
    fd = sys.stdin.fileno()
    old = termios.tcgetattr(fd)
    try:
        tty.setraw(fd)
        key = sys.stdin.read(1)
        if key == '\x1b':
            key += sys.stdin.read(2)
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, old)
    return key


if __name__ == '__main__':
    rospy.init_node('turtle_controller')
    turtle = sys.argv[1]
    pub = rospy.Publisher('/%s/cmd_vel' % turtle, Twist, queue_size=10)
    speeds = {'\x1b[A': (2, 0), '\x1b[B': (-2, 0), '\x1b[D': (0, 2), '\x1b[C': (0, -2)}
    while not rospy.is_shutdown():
        key = get_key()
        if key in ('q', '\x03'):
            break
        if key in speeds:
            t = Twist()
            t.linear.x, t.angular.z = speeds[key]
            pub.publish(t)
