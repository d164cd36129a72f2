#!/usr/bin/env python3
# -*- coding: utf-8 -*-
import os
import sys
import termios
import tty

import rospy
from geometry_msgs.msg import Twist

# Arrow keys codes
keys = {'\x1b[A': 'up', '\x1b[B': 'down', '\x1b[C': 'right', '\x1b[D': 'left', 's': 'stop', 'q': 'quit'}


def getchar():
    fd = sys.stdin.fileno()
    old = termios.tcgetattr(fd)
    try:
        tty.setcbreak(fd)
        return os.read(fd, 3).decode()
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, old)


if __name__ == '__main__':
    pub = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=10)
    rospy.init_node('mybot_teleop', anonymous=False)
    r = rospy.Rate(10)  # 10Hz
    try:
        while not rospy.is_shutdown():
            mykey = getchar()
            char = keys.get(mykey, '')
            message = Twist()
            if char == 'up':       # UP key
                message.linear.x = 2.0
            if char == 'down':     # DOWN key
                pass  # TODO
            if char == 'left':     # LEFT key
                message.angular.z = 2.0
            if char == 'right':    # RIGHT key
                pass  # TODO
            if char == 'quit':     # QUIT
                break
            pub.publish(message)
            r.sleep()
    except rospy.ROSInterruptException:
        pass
