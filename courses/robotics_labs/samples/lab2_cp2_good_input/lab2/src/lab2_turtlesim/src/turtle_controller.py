#!/usr/bin/env python
# Lab 2 turtle controller: rosrun lab2_turtlesim turtle_controller.py <turtle name>
# type w/a/s/d then Enter
import sys
import rospy
from geometry_msgs.msg import Twist

try:
    input = raw_input  # python 2
except NameError:
    pass


def controller(turtle):
    pub = rospy.Publisher('/' + turtle + '/cmd_vel', Twist, queue_size=10)
    r = rospy.Rate(10)
    while not rospy.is_shutdown():
        key = input('Move %s with w/a/s/d: ' % turtle)
        twist = Twist()
        if key == 'w':
            twist.linear.x = 2.0
        elif key == 's':
            twist.linear.x = -2.0
        elif key == 'a':
            twist.angular.z = 2.0
        elif key == 'd':
            twist.angular.z = -2.0
        else:
            continue
        pub.publish(twist)
        r.sleep()


if __name__ == '__main__':
    rospy.init_node('turtle_controller', anonymous=True)
    try:
        controller(sys.argv[1])
    except (rospy.ROSInterruptException, EOFError):
        pass
