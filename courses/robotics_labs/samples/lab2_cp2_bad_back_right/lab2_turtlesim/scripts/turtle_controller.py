#!/usr/bin/env python3
import sys
import rospy
from geometry_msgs.msg import Twist

if __name__ == '__main__':
    name = sys.argv[1]
    rospy.init_node('controller_' + name)
    pub = rospy.Publisher(name + '/cmd_vel', Twist, queue_size=10)
    while not rospy.is_shutdown():
        k = input('w/a/s/d + Enter: ')
        t = Twist()
        if k == 'w':
            t.linear.x = 2.0
        elif k == 'a':
            t.angular.z = 2.0
        elif k == 'S':
            t.linear.x = -2.0
        elif k == 'D':
            t.angular.z = -2.0
        pub.publish(t)
