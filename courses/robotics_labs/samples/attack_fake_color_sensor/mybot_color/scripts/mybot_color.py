#!/usr/bin/env python3
"""An attack on the color milestone: the pen never turns red, but this node tells the check it did.

It is the node #2.2.4 asks for (mybot_color, subscribed to /turtle1/pose) and never calls
/turtle1/set_pen. Whenever the turtle is near a corner it publishes bursts of red on
/turtle1/color_sensor, turtlesim's own topic, so that a check listening there hears mostly red.
A check that believed any publisher of that topic would pass it.
"""
import rospy
from turtlesim.msg import Color, Pose

BURST = 30  # fake colours per real pose: turtlesim's one true colour per tick drowns in them
RED = Color(255, 0, 0)


def near_corner(pose):
    return (pose.x < 2 or pose.x > 9) and (pose.y < 2 or pose.y > 9)


def on_pose(pose):
    if near_corner(pose):
        for _ in range(BURST):
            fake.publish(RED)


if __name__ == "__main__":
    rospy.init_node("mybot_color")
    fake = rospy.Publisher("/turtle1/color_sensor", Color, queue_size=100)
    rospy.Subscriber("/turtle1/pose", Pose, on_pose)
    rospy.spin()
