#!/usr/bin/env python3
"""Milestone 2.2 (UPMC part 1): drive the turtle into a corner, along a side and into the next
corner; the colour under the turtle (/turtle1/color_sensor) must be red only in the corners and
the default pen elsewhere. Near a side the background parameters change and /clear repaints."""
import math
import threading
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Color, Pose
from turtlesim.srv import TeleportAbsolute

from course_testkit.waiting import wait_for

RED, PEN = (255, 0, 0), (179, 184, 255)
DEFAULT_BACKGROUND = (69, 86, 255)
WORLD = 499.0 / 45.0
CORNER, SLACK = 2.0, 0.35  # corner margin of the text's plan; slack for one tick of lag


def region(x, y):
    """'corner' well inside a corner, 'middle' well outside, None near the border."""
    def near(v, m):
        return v < m or v > WORLD - m
    if near(x, CORNER - SLACK) and near(y, CORNER - SLACK):
        return "corner"
    if not (near(x, CORNER + SLACK) and near(y, CORNER + SLACK)):
        return "middle"
    return None


class ColorMilestone(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.pose = None
        self.samples = []  # (x, y, (r, g, b))
        rospy.Subscriber("/turtle1/pose", Pose, self.on_pose, tcp_nodelay=True)
        rospy.Subscriber("/turtle1/color_sensor", Color, self.on_color, tcp_nodelay=True)
        self.cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        rospy.wait_for_service("/turtle1/teleport_absolute", 30)
        self.teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        self.assertTrue(wait_for(lambda: self.pose, 20), "no pose from turtlesim")
        # the node under test is up once it subscribes to the pose
        self.assertTrue(wait_for(lambda: self.cmd.get_num_connections() and self.node_listening(), 30),
                        "the colour node does not subscribe to /turtle1/pose")

    def node_listening(self):
        import rosgraph
        master = rosgraph.Master("/milestone_color")
        _, subs, _ = master.getSystemState()
        return any(topic == "/turtle1/pose" and any("mybot_color" in n for n in nodes) for topic, nodes in subs)

    def on_pose(self, msg):
        with self.lock:
            self.pose = msg

    def on_color(self, msg):
        with self.lock:
            if self.pose is not None and self.recording:
                self.samples.append((self.pose.x, self.pose.y, (msg.r, msg.g, msg.b)))

    recording = False

    def drive(self, x, y, theta, speed, seconds, watch=None):
        self.teleport(x, y, theta)
        wait_for(lambda: abs(self.pose.x - x) < 0.05 and abs(self.pose.y - y) < 0.05, 5)
        self.recording = True
        end = rospy.get_time() + seconds
        rate = rospy.Rate(20)
        while rospy.get_time() < end and not rospy.is_shutdown():
            twist = Twist()
            twist.linear.x = speed
            self.cmd.publish(twist)
            if watch:
                watch()
            rate.sleep()
        self.cmd.publish(Twist())
        self.recording = False

    def test_red_in_corners_only_and_background_near_sides(self):
        backgrounds = set()

        def watch():
            if self.pose is not None and self.pose.y < 0.8:
                backgrounds.add(tuple(rospy.get_param("/turtlesim/background_" + c) for c in "rgb"))

        # down the left part of the canvas into the bottom-left corner, near the bottom side
        self.drive(1.5, 6.0, -math.pi / 2, 2.0, 2.9, watch)
        # along y = 1.5: out of the bottom-left corner, across, into the bottom-right corner
        self.drive(1.5, 1.5, 0.0, 2.0, 4.2)
        with self.lock:
            samples = list(self.samples)
        corner = [c for x, y, c in samples if region(x, y) == "corner"]
        middle = [c for x, y, c in samples if region(x, y) == "middle"]
        self.assertGreater(len(corner), 20, "too few samples in corners")
        self.assertGreater(len(middle), 20, "too few samples outside corners")
        red_in_corner = sum(1 for c in corner if c == RED) / len(corner)
        self.assertGreater(red_in_corner, 0.85, "pen not red in the corners (%.0f%% red)" % (100 * red_in_corner))
        red_outside = [c for c in middle if c == RED]
        self.assertFalse(red_outside, "red pen outside the corners (%d samples)" % len(red_outside))
        self.assertIn(PEN, middle, "default pen never seen outside the corners")
        self.assertTrue(backgrounds and DEFAULT_BACKGROUND not in backgrounds,
                        "background params did not change near the bottom side: %s" % backgrounds)
        self.assertTrue(wait_for(lambda: tuple(rospy.get_param("/turtlesim/background_" + c) for c in "rgb")
                                 == DEFAULT_BACKGROUND, 5),
                        "background params not restored after leaving the side")


if __name__ == "__main__":
    rospy.init_node("milestone_color")
    rostest.rosrun("mybot_color", "milestone_color", ColorMilestone)
