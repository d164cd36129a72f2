#!/usr/bin/env python3
# -*- coding: utf-8 -*-
import rospy
from turtlesim.msg import Pose
from turtlesim.srv import SetPen

in_corner = False


# Callback function for reading turtlesim node output
def read_pose_callback(msg):
    global in_corner
    rospy.loginfo("Current position: x=%.2f; y=%.2f" % (msg.x, msg.y))
    corner = (msg.x < 2 or msg.x > 9) and (msg.y < 2 or msg.y > 9)
    if corner and not in_corner:
        change_pen_color(255, 0, 0, 3, True)  # RED color
    elif in_corner and not corner:
        change_pen_color(179, 184, 255, 3, False)
    in_corner = corner


if __name__ == '__main__':
    try:
        rospy.init_node('mybot_color', anonymous=False, log_level=rospy.INFO, disable_signals=False)
        rospy.wait_for_service('/turtle1/set_pen')
        change_pen_color = rospy.ServiceProxy('/turtle1/set_pen', SetPen)
        sub = rospy.Subscriber('/turtle1/pose', Pose, read_pose_callback)
        rospy.spin()
    except rospy.ROSInterruptException:
        pass
