#!/usr/bin/env python3
# Part 5, done wrong: reads one pose with wait_for_message, then only keeps the node alive.
# It does subscribe, for its first message alone, so it prints where the turtle started and never
# where it goes.
import rospy
from turtlesim.msg import Pose

if __name__ == "__main__":
    rospy.init_node("pose_subscriber")
    pose = rospy.wait_for_message("/turtle1/pose", Pose)
    print("x=%.2f y=%.2f" % (pose.x, pose.y))
    rospy.spin()
