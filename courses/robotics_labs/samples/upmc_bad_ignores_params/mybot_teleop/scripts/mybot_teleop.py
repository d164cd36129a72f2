#!/usr/bin/env python3
import os
import select
import sys
import termios
import tty

import rospy
from geometry_msgs.msg import Twist

ARROWS = {'A': (1.0, 0.0), 'B': (-1.0, 0.0), 'C': (0.0, -1.0), 'D': (0.0, 1.0)}
SPEED = 2.0


def main():
    rospy.init_node('mybot_teleop')
    # parameters from the launch file
    if rospy.has_param('linear_scale'):
        linear_scale = rospy.get_param('linear_scale')
    else:
        linear_scale = 2.0
    angular_scale = rospy.get_param('angular_scale', 2.0)
    rospy.loginfo("scales: %s %s", linear_scale, angular_scale)
    topic_name = rospy.get_param('cmd_vel_topic_name', 'turtle1/cmd_vel')
    pub = rospy.Publisher(topic_name, Twist, queue_size=10)
    fd = sys.stdin.fileno()
    settings = termios.tcgetattr(fd)
    tty.setcbreak(fd)
    buf = ''
    try:
        while not rospy.is_shutdown():
            if not select.select([fd], [], [], 0.1)[0]:
                continue
            buf += os.read(fd, 1).decode()
            if buf in ('\x1b', '\x1b['):
                continue
            if buf.startswith('\x1b[') and buf[2:] in ARROWS:
                lin, ang = ARROWS[buf[2:]]
                msg = Twist()
                msg.linear.x = SPEED * lin
                msg.angular.z = SPEED * ang
                pub.publish(msg)
            elif buf == 'q':
                break
            buf = ''
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, settings)


if __name__ == '__main__':
    main()
