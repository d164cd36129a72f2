#!/usr/bin/env python3
"""patrol_server.py [TURTLE...]: offers /<turtle>/patrol (turtle_patrol/Patrol) for many turtles.

A call `rosservice call /turtle2/patrol vel omega x y theta` teleports that turtle to
(x, y, theta) and then keeps it circling with (vel, omega), 10 commands a second, until
the next call for it. One server serves every turtle: the ones named as arguments, and
(~discover, default true) every turtle it finds on the master (a .../pose topic of type
turtlesim/Pose), checked every second, so turtles spawned later get a service too.
Bad requests (NaN/inf, a pose off the canvas) fail with a message; the server keeps running.
"""
import math
import sys
import threading

import rospy
from geometry_msgs.msg import Twist
from turtlesim.srv import TeleportAbsolute

from turtle_patrol.srv import Patrol, PatrolResponse

WORLD_SIZE = 499.0 / 45.0  # turtlesim's canvas in metres


class TurtlePatrol:
    """The patrol service, publisher and current command of one turtle."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.cmd = None
        self.pub = rospy.Publisher("/%s/cmd_vel" % name, Twist, queue_size=1)
        self.teleport = rospy.ServiceProxy("/%s/teleport_absolute" % name, TeleportAbsolute)
        self.service = rospy.Service("/%s/patrol" % name, Patrol, self.handle)

    def handle(self, req):
        values = (req.vel, req.omega, req.x, req.y, req.theta)
        if not all(math.isfinite(v) for v in values):
            raise rospy.ServiceException("patrol values must be finite numbers, got %s" % (values,))
        if not (0.0 <= req.x <= WORLD_SIZE and 0.0 <= req.y <= WORLD_SIZE):
            raise rospy.ServiceException("x and y must be inside the canvas [0, %.2f]" % WORLD_SIZE)
        self.cmd = None  # stop the old patrol while teleporting
        self.pub.publish(Twist())
        try:
            self.teleport(req.x, req.y, req.theta)
        except rospy.ServiceException as err:
            raise rospy.ServiceException("could not teleport %s: %s" % (self.name, err))
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = req.vel, req.omega
        self.cmd = cmd
        rospy.loginfo("%s patrols at vel=%.2f omega=%.2f from (%.2f, %.2f, %.2f)"
                      % (self.name, req.vel, req.omega, req.x, req.y, req.theta))
        return PatrolResponse(cmd)

    def tick(self) -> None:
        if self.cmd is not None:
            self.pub.publish(self.cmd)


class PatrolServer:
    def __init__(self, names, discover: bool) -> None:
        self.lock = threading.Lock()
        self.turtles = {}
        for name in names:
            self.add(name.strip("/"))
        self.discover = discover
        rospy.Timer(rospy.Duration(0.1), self.tick)
        if discover:
            rospy.Timer(rospy.Duration(1.0), self.find_turtles)
            self.find_turtles(None)

    def add(self, name: str) -> None:
        with self.lock:
            if name and name not in self.turtles:
                self.turtles[name] = TurtlePatrol(name)
                rospy.loginfo("serving /%s/patrol" % name)

    def find_turtles(self, _event) -> None:
        try:
            topics = rospy.get_published_topics()
        except Exception as err:  # the master is briefly unreachable
            rospy.logwarn_throttle(5.0, "cannot list topics: %s" % err)
            return
        for topic, msg_type in topics:
            if msg_type == "turtlesim/Pose" and topic.endswith("/pose"):
                self.add(topic[1:-len("/pose")])

    def tick(self, _event) -> None:
        with self.lock:
            turtles = list(self.turtles.values())
        for turtle in turtles:
            try:
                turtle.tick()
            except rospy.ROSException:
                pass


if __name__ == "__main__":
    rospy.init_node("patrol_server")
    PatrolServer(rospy.myargv(sys.argv)[1:], bool(rospy.get_param("~discover", True)))
    rospy.spin()
