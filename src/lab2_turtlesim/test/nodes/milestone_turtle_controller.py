#!/usr/bin/env python3
"""Lab 2 checkpoint 2: `turtle_controller.py turtle1` and `turtle_controller.py turtle2`, each with
its own (pseudo-)terminal, drive their own turtle: up moves turtle1 forward, left turns turtle2,
and neither touches the other turtle."""
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.srv import Spawn

from course_testkit.keyboard import PtyKeyboard
from course_testkit.recorders import TopicRecorder


class ControllerMilestone(unittest.TestCase):
    def test_two_controllers_two_turtles(self):
        rospy.wait_for_service("/spawn", 30)
        rospy.ServiceProxy("/spawn", Spawn)(2.0, 2.0, 0.0, "turtle2")
        cmds = {t: TopicRecorder("/%s/cmd_vel" % t, Twist) for t in ("turtle1", "turtle2")}
        pkg, node_type = rospy.get_param("~node_pkg"), rospy.get_param("~node_type")
        keyboards = {t: PtyKeyboard.rosrun(pkg, node_type, [t]) for t in ("turtle1", "turtle2")}
        try:
            def press_until(turtle, key, check):
                return keyboards[turtle].press_until(key, lambda: any(check(m) for m in cmds[turtle].messages))
            self.assertTrue(press_until("turtle1", "up", lambda m: m.linear.x > 0), "turtle1 got no forward command")
            self.assertTrue(press_until("turtle2", "left", lambda m: m.angular.z > 0), "turtle2 got no left turn")
            self.assertFalse(any(m.angular.z > 0 for m in cmds["turtle1"].messages), "turtle1 got turtle2's key")
            self.assertFalse(any(m.linear.x > 0 for m in cmds["turtle2"].messages), "turtle2 got turtle1's key")
        finally:
            for k in keyboards.values():
                k.stop()


if __name__ == "__main__":
    rospy.init_node("milestone_turtle_controller")
    rostest.rosrun("lab2_turtlesim", "milestone_turtle_controller", ControllerMilestone)
