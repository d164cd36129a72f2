#!/usr/bin/env python
# usage: rosrun turtle_patrol patrol_server.py turtle1 turtle2 ...  (one server for all of them)
import sys
import rospy
from geometry_msgs.msg import Twist
from turtle_patrol.srv import Patrol, PatrolResponse
from turtlesim.srv import TeleportAbsolute


class Patroller(object):
    def __init__(self, name):
        self.name = name
        self.cmd = None
        self.pub = rospy.Publisher('/%s/cmd_vel' % name, Twist, queue_size=1)
        self.teleport = rospy.ServiceProxy('/%s/teleport_absolute' % name, TeleportAbsolute)
        rospy.Service('/%s/patrol' % name, Patrol, self.handle)

    def handle(self, req):
        self.cmd = None
        self.teleport(req.x, req.y, req.theta)
        cmd = Twist()
        cmd.linear.x = req.vel
        cmd.angular.z = req.omega
        self.cmd = cmd
        return PatrolResponse(cmd)

    def tick(self, event):
        if self.cmd is not None:
            self.pub.publish(self.cmd)


if __name__ == '__main__':
    rospy.init_node('patrol_server')
    names = rospy.myargv(sys.argv)[1:] or ['turtle1']
    patrollers = [Patroller(n) for n in names]
    rospy.Timer(rospy.Duration(0.1), lambda e: [p.tick(e) for p in patrollers])
    rospy.spin()
