#!/usr/bin/env python3
"""turtle_teleop_key on a pty: banner, one Twist per arrow with upstream scales, q quits, no TTY fails."""
import subprocess
import sys
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist

from turtlesim.msg import Pose
from course_checks.keyboard import PtyKeyboard
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

NODE = sys.argv[1:3] if len(sys.argv) >= 3 and not sys.argv[1].startswith("__") else ["turtlesim", "turtle_teleop_key"]


class TeleopKey(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("teleop_key_check")
        rospy.wait_for_service("/spawn", 20)

    def setUp(self):
        self.cmds = []
        self.sub = rospy.Subscriber("/turtle1/cmd_vel", Twist, self.cmds.append)
        self.teleop = PtyKeyboard(["rosrun"] + NODE, output_on_pty=True)

    def tearDown(self):
        self.teleop.stop()
        self.sub.unregister()

    def press(self, key: str) -> Twist:
        before = len(self.cmds)
        self.teleop.press(key)
        self.assertTrue(wait_for(lambda: len(self.cmds) > before, 5), "no Twist after %s" % key)
        return self.cmds[-1]

    def warm_up(self) -> None:
        """The first Twist can race the publisher's side of the new connection: press until one arrives."""
        self.assertTrue(self.teleop.press_until("up", lambda: self.cmds, tries=10),
                        "no Twist from the teleop after 10 presses")

    def test_arrows_publish_scaled_twists_and_q_quits(self):
        self.assertTrue(self.teleop.read_until(b"Use arrow keys to move the turtle. 'q' to quit."),
                        self.teleop.terminal_text)
        self.assertIn(b"Reading from keyboard", self.teleop.terminal_text)
        self.assertTrue(wait_for(lambda: self.sub.get_num_connections() > 0, 10))
        self.warm_up()
        up = self.press("up")
        self.assertEqual((up.linear.x, up.angular.z), (2.0, 0.0))
        self.assertEqual(self.press("down").linear.x, -2.0)
        self.assertEqual(self.press("left").angular.z, 2.0)
        self.assertEqual(self.press("right").angular.z, -2.0)
        self.teleop.press("x")  # unbound keys publish nothing
        count = len(self.cmds)
        self.teleop.press("q")
        self.assertEqual(self.teleop.wait(10), 0)
        self.assertEqual(len(self.cmds), count)

    def test_the_turtle_moves(self):
        pose = TopicRecorder("/turtle1/pose", Pose)
        start = pose.wait()
        self.assertTrue(self.teleop.read_until(b"'q' to quit."))
        # turtlesim's connection to the new teleop may come up after ours: press until the turtle moves
        def moved(p) -> bool:
            return abs(p.x - start.x) > 0.5 or abs(p.y - start.y) > 0.5

        self.assertIsNotNone(self.teleop.press_until("up", lambda: pose.wait(moved, timeout=0.0), tries=10,
                                                     interval=1.5),
                             "the turtle did not move after 10 presses of up")
        pose.unregister()

    def test_without_a_terminal_it_fails_clearly(self):
        proc = subprocess.run(["rosrun"] + NODE, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, timeout=30)
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("not a terminal", proc.stdout)


if __name__ == "__main__":
    rostest.rosrun("turtlesim", "teleop_key", TeleopKey)
