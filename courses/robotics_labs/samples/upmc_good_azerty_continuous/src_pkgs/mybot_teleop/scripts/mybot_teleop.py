#!/usr/bin/env python3
# -*- coding: utf-8 -*-
"""Téléopération clavier AZERTY : z avancer, s reculer, q gauche, d droite, espace arrêt, Ctrl+C quitter.
La commande est publiée en continu à 10 Hz (la tortue avance tant qu'on n'appuie pas sur espace)."""
import select
import sys
import termios
import tty

import rospy
from geometry_msgs.msg import Twist

TOUCHES = {'z': (1, 0), 's': (-1, 0), 'q': (0, 1), 'd': (0, -1), ' ': (0, 0)}


def lire_touche(timeout):
    fd = sys.stdin.fileno()
    ancien = termios.tcgetattr(fd)
    try:
        tty.setraw(fd)
        prets, _, _ = select.select([sys.stdin], [], [], timeout)
        return sys.stdin.read(1) if prets else ''
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, ancien)


def parametre(nom, defaut):
    if rospy.has_param(nom):
        return rospy.get_param(nom)
    return defaut


if __name__ == '__main__':
    rospy.init_node('mybot_teleop', anonymous=False)
    topic = parametre('cmd_vel_topic_name', '/turtle1/cmd_vel')
    vitesse_lin = float(parametre('linear_scale', 1.5))
    vitesse_ang = float(parametre('angular_scale', 1.5))
    pub = rospy.Publisher(topic, Twist, queue_size=1)
    r = rospy.Rate(10)
    lin, ang = 0, 0
    print("Commande envoyée sur " + topic + " (z/q/s/d, espace = stop)")
    try:
        while not rospy.is_shutdown():
            c = lire_touche(0.05)
            if c == '\x03':
                break
            if c in TOUCHES:
                lin, ang = TOUCHES[c]
            msg = Twist()
            msg.linear.x = vitesse_lin * lin
            msg.angular.z = vitesse_ang * ang
            pub.publish(msg)
            r.sleep()
    except rospy.ROSInterruptException:
        pass
