#!/usr/bin/env python3
# One server for the whole army: rosservice call /patrol <turtle_name> vel omega x y theta
import rospy
from geometry_msgs.msg import Twist
from turtlesim.srv import TeleportAbsolute
from turtle_patrol.srv import Patrol, PatrolResponse

publishers = {}
commands = {}


def patrol_callback(request):
    name = request.turtle_name.strip("/")
    if name not in publishers:
        publishers[name] = rospy.Publisher("/%s/cmd_vel" % name, Twist, queue_size=10)
    commands.pop(name, None)
    rospy.wait_for_service("/%s/teleport_absolute" % name)
    rospy.ServiceProxy("/%s/teleport_absolute" % name, TeleportAbsolute)(request.x, request.y, request.theta)
    cmd = Twist()
    cmd.linear.x = request.vel
    cmd.angular.z = request.omega
    commands[name] = cmd
    return PatrolResponse(cmd)


def drive(event):
    for name, cmd in list(commands.items()):
        publishers[name].publish(cmd)


if __name__ == "__main__":
    rospy.init_node("patrol_server")
    rospy.Service("/patrol", Patrol, patrol_callback)
    rospy.Timer(rospy.Duration(0.1), drive)
    rospy.spin()
