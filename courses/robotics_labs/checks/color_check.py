#!/usr/bin/env python3
"""Milestone `color` (001 2.2 Part B, #2.2.4-#2.2.7): an executable of the text's package starts
the node mybot_color subscribed to /turtle1/pose; while this check drives turtle1 in circles deep
in each corner the pen turns red, and back to another colour in the middle of the canvas. The
corner size is the student's (the text gives none): the circles stay within 0.7 m of both walls.
The pen colour is read from turtlesim's /turtle1/color_sensor. Checks: courses/robotics_labs/milestones/color.md."""
import os
import threading

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Color, Pose
from turtlesim.srv import TeleportAbsolute

from course_rospy import quick_exit
from course_format import causes
from course_milestones import students
import pen_spots as ps
from course_milestones import guard
from course_milestones.discovery import subscribes
from course_milestones.milestone_case import MilestoneCase
from course_milestones.trusted import TURTLESIM
from course_checks.artifacts import save_canvas
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

SPOT_TIMEOUT = 6.0  # s for the pen to change after the turtle arrives


class ColourRecorder:
    """The colours under turtle1 since the last reset (thread-safe)."""

    def __init__(self):
        self._lock = threading.Lock()
        self._colours = []
        self.sub = rospy.Subscriber("/turtle1/color_sensor", Color, self._on_colour, tcp_nodelay=True)

    def _on_colour(self, msg):
        with self._lock:
            self._colours.append((msg.r, msg.g, msg.b))

    def reset(self):
        with self._lock:
            self._colours = []

    def colours(self):
        with self._lock:
            return list(self._colours)


@guard.judged  # a violation of the trust policy fails the test, first
class ColorMilestone(MilestoneCase):

    def circle_until(self, spot, teleport, cmd, colours):
        """Teleport to `spot` and drive a circle there until the pen is red (corner) or not red
        (middle); whether it happened, and the last colour seen."""
        teleport(*spot.start())
        colours.reset()
        linear, angular = ps.circle_command()
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        deadline = rospy.get_time() + SPOT_TIMEOUT
        rate = rospy.Rate(20)
        while not ps.settled(colours.colours(), spot.corner) and rospy.get_time() < deadline:
            cmd.publish(twist)
            rate.sleep()
        cmd.publish(Twist())
        seen = colours.colours()
        return ps.settled(seen, spot.corner), (seen[-1] if seen else None)

    def test_pen_red_in_the_corners(self):
        pkg = rospy.get_param("~pkg")
        poses = TopicRecorder("/turtle1/pose", Pose)
        colours = ColourRecorder()
        cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        started = None
        try:
            self.assertTrue(wait_for(lambda: poses.last, 30),
                            causes.finding("course_tools", "turtlesim did not start (no /turtle1/pose)"))
            rospy.wait_for_service("/turtle1/teleport_absolute", 30)
            teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
            started, tried = students.start_registering(pkg, [], subscribes("/turtle1/pose"), hint="colou?r",
                                                        log_name=pkg)
            if started is None:
                self.fail(students.not_found_message(pkg, "subscribes to /turtle1/pose (#2.2.4)", tried))
            node = started.registration.node
            self.assertTrue(node.startswith("/mybot_color"), causes.finding(
                "wrong_name", "%s subscribes to /turtle1/pose from a node named %s; #2.2.4 asks for a node named "
                "mybot_color (rospy.init_node('mybot_color'))" % (os.path.basename(started.path), node)))
            self.assertTrue(wait_for(lambda: cmd.get_num_connections() > 0, 10),
                            causes.finding("course_tools", "turtlesim does not listen to us"))
            turned_red = False  # the pen turned red in a corner: the node did some of what was asked
            for spot in ps.tour():
                ok, last = self.circle_until(spot, teleport, cmd, colours)
                turned_red = turned_red or (ok and spot.corner)
                if not started.keyboard.node.running():
                    self.fail(causes.finding(causes.exited(turned_red),
                                             "%s exited (status %s) while the turtle was in the %s"
                                             % (os.path.basename(started.path), started.keyboard.node.proc.returncode,
                                                spot.name)))
                where = "(turtle circling around x=%.2f, y=%.2f)" % (spot.x, spot.y)
                if spot.corner:
                    self.assertTrue(ok, causes.finding(
                        "wrong_value", "the pen did not turn red in the %s corner %s within %.0f s: the line drawn "
                        "there is %s; #2.2.7 asks for a red line near the corners" % (spot.name, where, SPOT_TIMEOUT,
                                                                                     last)))
                else:
                    self.assertTrue(ok, causes.finding(
                        "wrong_value", "the pen stayed red after the turtle left the corner for the %s %s: the line "
                        "drawn there is %s; #2.2.7 asks for red only near the corners" % (spot.name, where, last)))
        finally:
            if started is not None:
                started.keyboard.end()
            save_canvas()
            poses.unregister()
            colours.sub.unregister()


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("color_check")
    guard.install([TURTLESIM])  # before any student code: believe only this simulator
    rostest.rosrun("course_milestones", "color", ColorMilestone)
