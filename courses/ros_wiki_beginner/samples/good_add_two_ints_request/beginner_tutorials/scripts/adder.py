#!/usr/bin/env python3
"""The add_two_ints service, kept in a class that counts the calls."""
import rospy
from beginner_tutorials.srv import AddTwoInts, AddTwoIntsResponse


class Adder:
    def __init__(self):
        self.calls = 0
        self.service = rospy.Service("/add_two_ints", AddTwoInts, self.handle)

    def handle(self, req):
        self.calls += 1
        response = AddTwoIntsResponse()
        response.sum = req.a + req.b
        return response


if __name__ == "__main__":
    rospy.init_node("add_two_ints_server")
    Adder()
    print("Ready to add two ints.")
    rospy.spin()
