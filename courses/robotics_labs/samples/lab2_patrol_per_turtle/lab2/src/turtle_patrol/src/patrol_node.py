#!/usr/bin/env python
# usage: rosrun turtle_patrol patrol_node.py TURTLE_NAME   (one per turtle)
import sys
import rospy
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty
from turtle_patrol.srv import Patrol
from turtlesim.srv import TeleportAbsolute

turtle = sys.argv[1]


def patrol_callback(request):
    rospy.wait_for_service('clear')
    rospy.wait_for_service('/' + turtle + '/teleport_absolute')
    clear_proxy = rospy.ServiceProxy('clear', Empty)
    teleport_proxy = rospy.ServiceProxy('/' + turtle + '/teleport_absolute', TeleportAbsolute)
    pub = rospy.Publisher('/' + turtle + '/cmd_vel', Twist, queue_size=50)
    cmd = Twist()
    cmd.linear.x = request.vel
    cmd.angular.z = request.omega
    rate = rospy.Rate(5)
    teleport_proxy(request.x0, request.y0, request.theta0)
    clear_proxy()
    while not rospy.is_shutdown():
        pub.publish(cmd)
        rate.sleep()
    return cmd  # never reached


if __name__ == '__main__':
    rospy.init_node(turtle + '_patrol_server')
    rospy.Service('/' + turtle + '/patrol', Patrol, patrol_callback)
    rospy.loginfo('Running patrol server for ' + turtle)
    rospy.spin()
