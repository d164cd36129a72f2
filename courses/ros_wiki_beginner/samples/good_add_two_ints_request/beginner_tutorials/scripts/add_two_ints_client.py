#!/usr/bin/env python3
import argparse

import rospy
from beginner_tutorials.srv import AddTwoInts, AddTwoIntsRequest

parser = argparse.ArgumentParser(description="add two integers with the add_two_ints service")
parser.add_argument("x", type=int)
parser.add_argument("y", type=int)
args = parser.parse_args(rospy.myargv()[1:])

rospy.init_node("add_two_ints_client", anonymous=True)
rospy.wait_for_service("add_two_ints", timeout=20)
proxy = rospy.ServiceProxy("add_two_ints", AddTwoInts)
request = AddTwoIntsRequest(a=args.x, b=args.y)
answer = proxy.call(request)
print("{} + {} = {}".format(request.a, request.b, answer.sum))
