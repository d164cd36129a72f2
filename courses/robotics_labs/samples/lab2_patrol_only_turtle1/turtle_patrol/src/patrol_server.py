#!/usr/bin/env python
from geometry_msgs.msg import Twist
import rospy
from std_srvs.srv import Empty
from turtle_patrol.srv import Patrol
from turtlesim.srv import TeleportAbsolute


def patrol_callback(request):
    rospy.wait_for_service('clear')
    rospy.wait_for_service('/turtle1/teleport_absolute')
    clear_proxy = rospy.ServiceProxy('clear', Empty)
    teleport_proxy = rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)
    pub = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=50)
    cmd = Twist()
    cmd.linear.x = request.vel
    cmd.angular.z = request.omega
    rate = rospy.Rate(5)
    teleport_proxy(request.x, request.y, request.theta)
    clear_proxy()
    while not rospy.is_shutdown():
        pub.publish(cmd)
        rate.sleep()
    return cmd


def patrol_server():
    rospy.init_node('turtle1_patrol_server')
    rospy.Service('/turtle1/patrol', Patrol, patrol_callback)
    rospy.loginfo('Running patrol server...')
    rospy.spin()


if __name__ == '__main__':
    patrol_server()
