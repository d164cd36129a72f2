#!/usr/bin/env python3
import sys

import rospy
from beginner_tutorials.srv import AddTwoInts

if len(sys.argv) < 3:
    print("usage: add_two_ints_client.py x y")
    sys.exit(1)
x = sys.argv[1]
y = sys.argv[2]
rospy.wait_for_service("add_two_ints")
add_two_ints = rospy.ServiceProxy("add_two_ints", AddTwoInts)
add_two_ints(int(x), int(y))
print("%s + %s = %s" % (x, y, x + y))
