#!/usr/bin/env python3
"""Milestone 2.3.3 (UPMC part 1): the teleop node teleoperates the simulated TurtleBot3 Burger.

The world, the Burger and the parameters come from turtlebot3_empty_world.launch (included by
the .test file with teleop:=false); the node under test runs here on a pseudo-terminal. Keys
typed into it must become Twists on /cmd_vel scaled by linear_scale/angular_scale, and the
Burger must answer on /odom: up drives forward, left turns, s stops, q quits with status 0."""
import math
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from course_testkit.keyboard import PtyKeyboard
from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for

BURGER_MAX_LINEAR = 0.22   # m/s, TurtleBot3 Burger limit
BURGER_MAX_ANGULAR = 2.84  # rad/s
SIM_START_TIMEOUT = 90.0   # wall seconds for the simulator to start and spawn the Burger
MOTION_TIMEOUT = 30.0      # wall seconds for the Burger to show a commanded motion on /odom


def yaw_of(odom: Odometry) -> float:
    """Heading (rad) of an odometry pose, from its quaternion."""
    q = odom.pose.pose.orientation
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def angle_between(a: float, b: float) -> float:
    """Smallest absolute difference between two headings."""
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


class TurtlebotMilestone(unittest.TestCase):
    def setUp(self):
        self.cmds = TopicRecorder("/cmd_vel", Twist)
        self.odom = TopicRecorder("/odom", Odometry)
        self.assertTrue(wait_for(lambda: self.odom.last, SIM_START_TIMEOUT),
                        "no /odom: the simulator did not start or the Burger was not spawned")
        self.linear_scale = float(rospy.get_param("/linear_scale"))
        self.angular_scale = float(rospy.get_param("/angular_scale"))
        self.keyboard = PtyKeyboard.rosrun(rospy.get_param("~node_pkg"), rospy.get_param("~node_type"),
                                           ["__name:=teleop"])

    def tearDown(self):
        self.keyboard.stop()
        self.cmds.unregister()
        self.odom.unregister()

    def press_until_command(self, key, check):
        """Press a key (again every second: the node may still be starting, or its publisher
        not yet connected) until a /cmd_vel message satisfying check() arrives; return it."""
        self.cmds.clear()
        found = self.keyboard.press_until(key, lambda: [m for m in self.cmds.messages if check(m)], tries=30)
        if found:
            return found[-1]
        self.assertTrue(self.keyboard.node.running(), "the teleop node exited before key %r" % key)
        self.fail("no command for key %r on /cmd_vel" % key)

    def odom_after(self, start: Odometry, sim_seconds: float):
        """The first odometry at least sim_seconds of simulated time after start (None on timeout)."""
        due = start.header.stamp.to_sec() + sim_seconds
        return wait_for(lambda: self.odom.last if self.odom.last.header.stamp.to_sec() >= due else None,
                        MOTION_TIMEOUT)

    def test_keys_drive_the_burger(self):
        self.assertEqual(rospy.get_param("/cmd_vel_topic_name").strip("/"), "cmd_vel")
        self.assertTrue(0 < self.linear_scale <= BURGER_MAX_LINEAR, "linear_scale %s is outside the Burger's "
                        "range (0, %s]" % (self.linear_scale, BURGER_MAX_LINEAR))
        self.assertTrue(0 < self.angular_scale <= BURGER_MAX_ANGULAR, "angular_scale %s is outside the Burger's "
                        "range (0, %s]" % (self.angular_scale, BURGER_MAX_ANGULAR))

        # up: forward at linear_scale, and the Burger moves forward
        start = self.odom.last
        up = self.press_until_command("up", lambda m: m.linear.x > 0)
        self.assertAlmostEqual(up.linear.x, self.linear_scale, places=3)
        self.assertAlmostEqual(up.angular.z, 0.0, places=3)
        x0 = start.pose.pose.position.x
        # the simulator's connection to the new node may come up after ours: press until the Burger moves
        self.assertTrue(self.keyboard.press_until("up", lambda: self.odom.last.pose.pose.position.x > x0 + 0.05,
                                                  tries=10, interval=MOTION_TIMEOUT / 10),
                        "the Burger did not move 5 cm forward after the up arrow (x %.3f -> %.3f)"
                        % (x0, self.odom.last.pose.pose.position.x))

        # left: turn counter-clockwise at angular_scale, and the heading changes
        before_turn = self.odom.last
        left = self.press_until_command("left", lambda m: m.angular.z > 0)
        self.assertAlmostEqual(left.angular.z, self.angular_scale, places=3)
        self.assertAlmostEqual(left.linear.x, 0.0, places=3)
        yaw0 = yaw_of(before_turn)
        self.assertTrue(wait_for(lambda: angle_between(yaw_of(self.odom.last), yaw0) > 0.1, MOTION_TIMEOUT),
                        "the Burger did not turn after the left arrow")
        self.assertTrue(wait_for(lambda: self.odom.last.twist.twist.angular.z > 0.5 * self.angular_scale,
                                 MOTION_TIMEOUT), "the Burger does not turn left on /odom")

        # s: a zero Twist, and the Burger comes to rest and stays there
        stop = self.press_until_command("s", lambda m: m.linear.x == 0 and m.angular.z == 0)
        self.assertEqual((stop.linear.y, stop.linear.z, stop.angular.x, stop.angular.y), (0, 0, 0, 0))

        def at_rest():
            twist = self.odom.last.twist.twist
            return abs(twist.linear.x) < 0.005 and abs(twist.angular.z) < 0.01
        self.assertTrue(wait_for(at_rest, MOTION_TIMEOUT), "the Burger did not stop after 's'")
        rest = self.odom.last
        later = self.odom_after(rest, 0.5)
        self.assertIsNotNone(later, "the simulation clock stopped")
        moved = math.hypot(later.pose.pose.position.x - rest.pose.pose.position.x,
                           later.pose.pose.position.y - rest.pose.pose.position.y)
        self.assertLess(moved, 0.005, "the Burger still drifts after 's'")
        self.assertLess(angle_between(yaw_of(later), yaw_of(rest)), 0.01, "the Burger still turns after 's'")

        # q: the node quits cleanly
        self.keyboard.press("q")
        self.assertTrue(wait_for(lambda: not self.keyboard.node.running(), 10), "q did not quit the node")
        self.assertEqual(self.keyboard.node.proc.returncode, 0, "the node did not exit with status 0 on q")


if __name__ == "__main__":
    rospy.init_node("milestone_turtlebot")
    rostest.rosrun("mybot_teleop", "milestone_turtlebot", TurtlebotMilestone)
