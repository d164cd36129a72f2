#!/usr/bin/env python3
"""patrol_server.py [TURTLE...]: offers /<turtle>/patrol (turtle_patrol/Patrol) for many turtles.

A call `rosservice call /turtle2/patrol vel omega x y theta` teleports that turtle to
(x, y, theta) and then keeps it circling with (vel, omega), 10 commands a second, until
the next call for it. One server serves every turtle: the ones named as arguments, and
(~discover, default true) every turtle it finds on the master (a .../pose topic of type
turtlesim/Pose), checked every second, so turtles spawned later get a service too.
Bad requests (NaN/inf, a pose off the canvas, a speed no tick can draw) fail with a
message; the server keeps running and never sends turtlesim such numbers.
"""
import math
import sys
import threading
from typing import Optional

import rospy
from geometry_msgs.msg import Twist
from turtlesim.srv import TeleportAbsolute

from turtle_patrol.srv import Patrol, PatrolResponse

# Upstream turtlesim's canvas (500 px at 45 px/m) and tick (62.5 Hz). The patrol runs against any
# turtlesim, upstream's included, which ships no Python module to import them from; the unit
# tests check they equal our simulator's turtlesim.constants.
WORLD_SIZE = 499.0 / 45.0
TICK = 0.016
MAX_VEL = WORLD_SIZE / TICK
"""m/s: faster, one turtlesim tick would cross the whole canvas (693 m/s)."""
MAX_OMEGA = math.pi / TICK
"""rad/s: faster, one tick would turn more than half a turn and no circle is drawn (196 rad/s)."""


def request_error(vel: float, omega: float, x: float, y: float, theta: float) -> Optional[str]:
    """Why a patrol request cannot be served, or None when it can."""
    values = (vel, omega, x, y, theta)
    if not all(math.isfinite(v) for v in values):
        return "patrol values must be finite numbers, got %s" % (values,)
    if abs(vel) > MAX_VEL:
        return "vel=%g is too fast: |vel| must be <= %.1f m/s (one tick would cross the canvas)" % (vel, MAX_VEL)
    if abs(omega) > MAX_OMEGA:
        return ("omega=%g is too fast: |omega| must be <= %.1f rad/s (one tick would turn more than "
                "half a turn)" % (omega, MAX_OMEGA))
    if not (0.0 <= x <= WORLD_SIZE and 0.0 <= y <= WORLD_SIZE):
        return "x and y must be inside the canvas [0, %.2f]" % WORLD_SIZE
    return None


class TurtlePatrol:
    """The patrol service, publisher and current command of one turtle."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.cmd = None
        self.pub = rospy.Publisher("/%s/cmd_vel" % name, Twist, queue_size=1)
        self.teleport = rospy.ServiceProxy("/%s/teleport_absolute" % name, TeleportAbsolute)
        self.service = rospy.Service("/%s/patrol" % name, Patrol, self.handle)

    def handle(self, req):
        problem = request_error(req.vel, req.omega, req.x, req.y, req.theta)
        if problem:
            raise rospy.ServiceException(problem)
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
