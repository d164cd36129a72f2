#!/usr/bin/env python3
import sys
import rospy
from geometry_msgs.msg import Twist


def main():
    turtle_name = sys.argv[1]
    rospy.init_node(turtle_name + '_controller')
    pub = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=10)
    print("controlling " + turtle_name)
    while not rospy.is_shutdown():
        cmd = input()
        msg = Twist()
        if cmd == 'w':
            msg.linear.x = 1.0
        if cmd == 's':
            msg.linear.x = -1.0
        if cmd == 'a':
            msg.angular.z = 1.0
        if cmd == 'd':
            msg.angular.z = -1.0
        pub.publish(msg)


if __name__ == '__main__':
    main()
