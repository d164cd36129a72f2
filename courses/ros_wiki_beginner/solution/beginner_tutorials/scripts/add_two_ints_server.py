#!/usr/bin/env python3
"""add_two_ints_server.py: offers the service add_two_ints (beginner_tutorials/AddTwoInts): sum = a + b."""
import rospy
from beginner_tutorials.srv import AddTwoInts, AddTwoIntsResponse


def add(request):
    total = request.a + request.b
    rospy.loginfo("Returning [%d + %d = %d]", request.a, request.b, total)
    return AddTwoIntsResponse(total)


def main():
    rospy.init_node("add_two_ints_server")
    rospy.Service("add_two_ints", AddTwoInts, add)
    rospy.loginfo("Ready to add two ints.")
    rospy.spin()


if __name__ == "__main__":
    main()
