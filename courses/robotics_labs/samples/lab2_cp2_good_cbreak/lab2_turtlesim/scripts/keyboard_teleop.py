#!/usr/bin/env python3
"""Drive the turtle named on the command line with single keys: w/s forward/backward, a/d turn,
space stops, q quits. The command is repeated at 10 Hz, so the turtle keeps going."""
import select
import sys
import termios
import tty

import rospy
from geometry_msgs.msg import Twist

MOVES = {"w": (1.5, 0.0), "s": (-1.5, 0.0), "a": (0.0, 1.5), "d": (0.0, -1.5), " ": (0.0, 0.0)}


def main(argv):
    if len(argv) < 2:
        print("usage: keyboard_teleop.py TURTLE")
        return 1
    name = argv[1]
    rospy.init_node("teleop_" + name)
    pub = rospy.Publisher(name + "/cmd_vel", Twist, queue_size=1)
    rate = rospy.Rate(10)
    current = (0.0, 0.0)
    old = termios.tcgetattr(sys.stdin)
    tty.setcbreak(sys.stdin.fileno())
    try:
        while not rospy.is_shutdown():
            if select.select([sys.stdin], [], [], 0)[0]:
                ch = sys.stdin.read(1)
                if ch == "q":
                    break
                current = MOVES.get(ch, current)
            msg = Twist()
            msg.linear.x, msg.angular.z = current
            pub.publish(msg)
            rate.sleep()
    finally:
        termios.tcsetattr(sys.stdin, termios.TCSADRAIN, old)
    return 0


if __name__ == "__main__":
    sys.exit(main(rospy.myargv(sys.argv)))
