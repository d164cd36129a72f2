#!/usr/bin/env python3
# -*- coding: utf-8 -*-
import rospy
from turtlesim.msg import Pose
from turtlesim.srv import SetPen

LIMITE_BAS, LIMITE_HAUT = 2.5, 8.5
dans_coin = False


def read_pose_callback(msg):
    global dans_coin
    rospy.loginfo("Current position: x=%.2f; y=%.2f" % (msg.x, msg.y))
    bord_x = msg.x < LIMITE_BAS or msg.x > LIMITE_HAUT
    bord_y = msg.y < LIMITE_BAS or msg.y > LIMITE_HAUT
    coin = bord_x and bord_y
    if coin != dans_coin:
        if coin:
            change_pen_color(255, 0, 0, 5, False)   # rouge
        else:
            change_pen_color(179, 184, 255, 3, False)  # couleur par défaut
        dans_coin = coin


if __name__ == '__main__':
    try:
        rospy.init_node('mybot_color', anonymous=False, log_level=rospy.INFO, disable_signals=False)
        rospy.wait_for_service('/turtle1/set_pen')
        change_pen_color = rospy.ServiceProxy('/turtle1/set_pen', SetPen)
        sub = rospy.Subscriber('/turtle1/pose', Pose, read_pose_callback)
        rospy.spin()
    except rospy.ROSInterruptException:
        pass
