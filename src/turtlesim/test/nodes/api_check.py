#!/usr/bin/env python3
"""turtlesim_node's ROS interface behaves like upstream turtlesim."""
import math
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty

from turtlesim.constants import CENTRE, DEFAULT_BACKGROUND_RGB, WORLD_SIZE
from turtlesim.msg import Color, Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative
from course_checks.recorders import RosoutRecorder, TopicRecorder
from course_checks.waiting import wait_for


def twist(x=0.0, y=0.0, z=0.0) -> Twist:
    t = Twist()
    t.linear.x, t.linear.y, t.angular.z = x, y, z
    return t


class TurtlesimApi(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("turtlesim_api_check")
        rospy.wait_for_service("/reset", 20)
        cls.rosout = RosoutRecorder()
        cls.reset = rospy.ServiceProxy("/reset", Empty)
        cls.clear = rospy.ServiceProxy("/clear", Empty)
        cls.spawn = rospy.ServiceProxy("/spawn", Spawn)
        cls.kill = rospy.ServiceProxy("/kill", Kill)

    def setUp(self):
        for p, v in zip("rgb", DEFAULT_BACKGROUND_RGB):
            rospy.set_param("/turtlesim/background_" + p, v)
        self.reset()
        rospy.wait_for_service("/turtle1/teleport_absolute", 5)
        self.pose = TopicRecorder("/turtle1/pose", Pose)
        self.colour = TopicRecorder("/turtle1/color_sensor", Color)
        self.cmd = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        self.assertTrue(wait_for(lambda: self.cmd.get_num_connections() > 0, 5))
        self.assertIsNotNone(self.pose.wait())

    def tearDown(self):
        self.pose.unregister()
        self.colour.unregister()
        self.cmd.unregister()

    def teleport(self, x, y, theta, turtle="turtle1"):
        rospy.ServiceProxy("/%s/teleport_absolute" % turtle, TeleportAbsolute)(x, y, theta)
        return self.pose.wait(lambda p: abs(p.x - x) < 1e-3 and abs(p.y - min(y, WORLD_SIZE)) < 1e-3)

    def drive(self, x=0.0, y=0.0, z=0.0):
        self.cmd.publish(twist(x, y, z))

    def test_graph_names_and_params(self):
        master = rosgraph.Master("/api_check")
        pubs, subs, srvs = master.getSystemState()
        pubs, subs, srvs = dict(pubs), dict(subs), dict(srvs)
        self.assertIn("/turtlesim", pubs["/turtle1/pose"])
        self.assertIn("/turtlesim", pubs["/turtle1/color_sensor"])
        self.assertIn("/turtlesim", subs["/turtle1/cmd_vel"])
        for srv in ("/clear", "/reset", "/spawn", "/kill", "/turtle1/set_pen",
                    "/turtle1/teleport_absolute", "/turtle1/teleport_relative"):
            self.assertIn(srv, srvs)
        self.assertEqual([rospy.get_param("/turtlesim/background_" + c) for c in "rgb"], [69, 86, 255])

    def test_start_pose_and_rate(self):
        p = self.pose.wait()
        self.assertAlmostEqual(p.x, CENTRE, places=4)
        self.assertAlmostEqual(p.y, CENTRE, places=4)
        start_count, start = self.pose.count, time.monotonic()
        time.sleep(2.0)  # measuring a rate over a window, not synchronising
        rate = (self.pose.count - start_count) / (time.monotonic() - start)
        self.assertGreater(rate, 50.0)
        self.assertLess(rate, 70.0)

    def test_forward_motion_then_timeout_stops(self):
        self.teleport(2.0, 2.0, 0.0)
        self.drive(x=1.0)
        moving = self.pose.wait(lambda p: p.linear_velocity == 1.0 and p.x > 2.05)
        self.assertIsNotNone(moving)
        stopped = self.pose.wait(lambda p: p.linear_velocity == 0.0, timeout=3.0)
        self.assertIsNotNone(stopped, "a command older than 1 s must stop the turtle")
        x = stopped.x
        self.assertAlmostEqual(x, 3.0, delta=0.2)
        self.assertAlmostEqual(self.pose.wait(lambda p: True).x, x, places=4)

    def test_holonomic_linear_y(self):
        self.teleport(5.0, 5.0, 0.0)
        self.drive(y=1.0)
        p = self.pose.wait(lambda p: p.y > 5.2)
        self.assertIsNotNone(p)
        self.assertAlmostEqual(p.x, 5.0, places=3)

    def test_theta_wraps_into_minus_pi_pi(self):
        self.teleport(5.0, 5.0, 3.1)
        self.drive(z=2.0)
        p = self.pose.wait(lambda p: -3.0 < p.theta < 0.0)
        self.assertIsNotNone(p, "theta must wrap from +pi to -pi")
        self.assertEqual(p.angular_velocity, 2.0)

    def test_wall_clamp_and_warning(self):
        self.teleport(0.3, 5.0, math.pi)
        self.drive(x=2.0)
        p = self.pose.wait(lambda p: p.x == 0.0)
        self.assertIsNotNone(p)
        self.assertAlmostEqual(p.y, 5.0, places=3)
        self.assertTrue(self.rosout.wait_for_text("Oh no! I hit the wall! (Clamping from [x=", level=4))

    def test_pen_and_colour_sensor(self):
        self.teleport(2.0, 2.0, 0.0)
        rospy.ServiceProxy("/turtle1/set_pen", SetPen)(255, 0, 0, 3, 0)
        self.drive(x=1.0)
        self.assertIsNotNone(self.colour.wait(lambda c: (c.r, c.g, c.b) == (255, 0, 0)))
        rospy.ServiceProxy("/turtle1/set_pen", SetPen)(0, 0, 0, 0, 1)
        self.teleport(8.0, 8.0, 0.0)
        self.drive(x=1.0)
        self.assertIsNotNone(self.colour.wait(lambda c: (c.r, c.g, c.b) == DEFAULT_BACKGROUND_RGB),
                             "with the pen off, the sensor sees the background")

    def test_default_pen_draws_while_teleporting(self):
        self.teleport(3.0, 3.0, 0.0)
        self.teleport(6.0, 3.0, 0.0)
        self.assertIsNotNone(self.colour.wait(lambda c: (c.r, c.g, c.b) == (179, 184, 255)))

    def test_teleport_relative(self):
        self.teleport(4.0, 4.0, 0.0)
        rospy.ServiceProxy("/turtle1/teleport_relative", TeleportRelative)(2.0, math.pi / 2)
        p = self.pose.wait(lambda p: abs(p.y - 6.0) < 1e-3)
        self.assertIsNotNone(p)
        self.assertAlmostEqual(p.x, 4.0, places=3)
        self.assertAlmostEqual(p.theta, math.pi / 2, places=3)

    def test_spawn_naming_duplicates_and_kill(self):
        self.assertEqual(self.spawn(1.0, 1.0, 0.0, "").name, "turtle2")
        self.assertEqual(self.spawn(2.0, 1.0, 0.0, "leonardo").name, "leonardo")
        with self.assertRaisesRegex(rospy.ServiceException, "already exists"):
            self.spawn(1.0, 1.0, 0.0, "leonardo")
        with self.assertRaisesRegex(rospy.ServiceException, "invalid turtle name"):
            self.spawn(1.0, 1.0, 0.0, "9 lives")
        leo = TopicRecorder("/leonardo/pose", Pose)
        p = leo.wait()
        self.assertAlmostEqual(p.x, 2.0, places=4)
        leo.unregister()
        self.kill("leonardo")
        master = rosgraph.Master("/api_check")
        self.assertTrue(wait_for(lambda: "/leonardo/pose" not in dict(master.getSystemState()[0])))
        self.assertTrue(wait_for(lambda: "/leonardo/set_pen" not in dict(master.getSystemState()[2])))
        with self.assertRaisesRegex(rospy.ServiceException, "which does not exist"):
            self.kill("leonardo")
        self.assertEqual(self.spawn(1.0, 1.0, 0.0, "").name, "turtle3")

    def test_clear_rereads_background_params(self):
        rospy.set_param("/turtlesim/background_r", 255)
        rospy.set_param("/turtlesim/background_g", 0)
        rospy.set_param("/turtlesim/background_b", 0)
        self.assertIsNotNone(self.colour.wait(lambda c: (c.r, c.g, c.b) == DEFAULT_BACKGROUND_RGB))
        self.clear()
        self.assertIsNotNone(self.colour.wait(lambda c: (c.r, c.g, c.b) == (255, 0, 0)))
        self.assertTrue(self.rosout.wait_for_text("Clearing turtlesim."))

    def test_reset_removes_turtles_and_recentres(self):
        self.spawn(1.0, 1.0, 0.0, "donatello")
        self.teleport(1.0, 9.0, 1.0)
        self.reset()
        master = rosgraph.Master("/api_check")
        self.assertTrue(wait_for(lambda: "/donatello/pose" not in dict(master.getSystemState()[0])))
        p = self.pose.wait(lambda p: abs(p.x - CENTRE) < 1e-4 and abs(p.y - CENTRE) < 1e-4 and p.theta == 0.0)
        self.assertIsNotNone(p)
        self.assertTrue(self.rosout.wait_for_text("Resetting turtlesim."))

    def test_reset_keeps_turtle1_pose_connection(self):
        """A node that calls /reset keeps its /turtle1/pose connection: turtle1's publisher is not
        re-advertised, so no subscriber has to win a reconnection race (arch drawer, 003 Task 7)."""
        self.assertTrue(wait_for(lambda: self.pose.sub.get_num_connections() == 1, 10))
        before = list(self.pose.sub.impl.connections)
        for _ in range(5):
            self.reset()
        self.pose.clear()
        self.assertIsNotNone(self.pose.wait(timeout=5), "no pose after the resets")
        self.assertEqual(list(self.pose.sub.impl.connections), before, "the pose connection was replaced")
        self.assertFalse(before[0].done, "the pose connection was closed")


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "turtlesim_api", TurtlesimApi)
