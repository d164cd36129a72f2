#!/usr/bin/env python3
"""patrol_server.py: offers /turtle1/patrol (turtle_patrol/Patrol). After a call, turtle1 goes round
a circle at the requested speed (vel) and turn rate (omega) until the next one; the response is
the Twist it keeps sending on /turtle1/cmd_vel."""
import rospy
from geometry_msgs.msg import Twist

from turtle_patrol.srv import Patrol, PatrolResponse


class Patroller:
    """Holds the command of the last call and publishes it ten times a second."""

    def __init__(self) -> None:
        self.cmd = Twist()
        self.pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        rospy.Service("/turtle1/patrol", Patrol, self.patrol)
        rospy.Timer(rospy.Duration(0.1), lambda _event: self.pub.publish(self.cmd))

    def patrol(self, req) -> PatrolResponse:
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = req.vel, req.omega
        self.cmd = cmd
        return PatrolResponse(cmd)


if __name__ == "__main__":
    rospy.init_node("patrol_server")
    Patroller()
    rospy.spin()
