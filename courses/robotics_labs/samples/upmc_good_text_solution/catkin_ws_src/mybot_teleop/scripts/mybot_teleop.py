#!/usr/bin/env python3
# -*- coding: utf-8 -*-
# mybot_teleop, after part C: topic and speeds come from the parameter server
import rospy
import sys, termios, tty, os
from geometry_msgs.msg import Twist

# Arrow keys codes
keys = {'\x1b[A': 'up', '\x1b[B': 'down', '\x1b[C': 'right', '\x1b[D': 'left', 's': 'stop', 'q': 'quit'}


def getkey():
    fd = sys.stdin.fileno()
    old = termios.tcgetattr(fd)
    tty.setcbreak(fd)
    try:
        return os.read(fd, 3).decode()
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, old)


if __name__ == '__main__':
    rospy.init_node('mybot_teleop', anonymous=False)
    # First, get the name of the topic to publish to
    if rospy.has_param('cmd_vel_topic_name'):
        topic_name = rospy.get_param('cmd_vel_topic_name')
    else:
        # If not set, the default topic is cmd_vel
        topic_name = 'cmd_vel'
    print("Command sent to " + topic_name)
    if rospy.has_param('linear_scale'):
        linear_scale = rospy.get_param('linear_scale')
    else:
        linear_scale = 2.0
    if rospy.has_param('angular_scale'):
        angular_scale = rospy.get_param('angular_scale')
    else:
        angular_scale = 2.0
    pub = rospy.Publisher(topic_name, Twist, queue_size=10)
    try:
        while not rospy.is_shutdown():
            char = keys.get(getkey())
            message = Twist()
            if char == 'up':
                message.linear.x = linear_scale * 1.0
            elif char == 'down':
                message.linear.x = linear_scale * -1.0
            elif char == 'left':
                message.angular.z = angular_scale * 1.0
            elif char == 'right':
                message.angular.z = angular_scale * -1.0
            elif char == 'quit':
                break
            elif char != 'stop':
                continue
            pub.publish(message)
    except rospy.ROSInterruptException:
        pass
