#!/usr/bin/env python3
"""add_two_ints_client.py X Y: asks the service add_two_ints for X + Y and prints "X + Y = SUM"."""
import sys

import rospy
from beginner_tutorials.srv import AddTwoInts


def ask(x, y):
    rospy.wait_for_service("add_two_ints")
    adder = rospy.ServiceProxy("add_two_ints", AddTwoInts)
    return adder(x, y).sum


def main(argv):
    words = rospy.myargv(argv)[1:]  # without the __name:= and name:= arguments ROS adds
    if len(words) != 2:
        print("usage: add_two_ints_client.py X Y")
        return 1
    x, y = int(words[0]), int(words[1])
    print("Requesting %d + %d" % (x, y))
    try:
        print("%d + %d = %d" % (x, y, ask(x, y)))
    except rospy.ServiceException as failure:
        print("Service call failed: %s" % failure)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
