#!/usr/bin/env python3
import rospy
from beginner_tutorials.srv import AddTwoInts


def handle_add(req):
    print("adding %s and %s" % (req.a, req.b))
    return req.a + req.b


rospy.init_node("add_two_ints_server")
s = rospy.Service("add_two_ints", AddTwoInts, handle_add)
print("Ready to add two ints.")
rospy.spin()
