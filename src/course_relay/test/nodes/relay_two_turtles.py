#!/usr/bin/env python3
"""One `rostopic pub -1 /turtle1/cmd_vel geometry_msgs/Twist ...` (a latched one-shot message)
moves both turtles of two_turtles.launch through their relays, as it does with topic_tools relay."""
import math
import subprocess
import unittest

import rosgraph
import rospy
import rostest
from turtlesim.msg import Pose

from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

NAMESPACES = ("/turtlesim1", "/turtlesim2")
COMMAND = ["rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--",
           "[2.0, 0.0, 0.0]", "[0.0, 0.0, 1.8]"]
MOVED_M = 0.5
TIMEOUT_S = 20


def distance(a: Pose, b: Pose) -> float:
    return math.hypot(a.x - b.x, a.y - b.y)


class RelayTwoTurtles(unittest.TestCase):
    def test_one_shot_twist_moves_both_turtles(self):
        poses = {ns: TopicRecorder(ns + "/turtle1/pose", Pose) for ns in NAMESPACES}
        self.assertTrue(wait_for(lambda: all(r.last for r in poses.values()), TIMEOUT_S), "no pose from a turtlesim")
        master = rosgraph.Master(rospy.get_name())
        self.assertTrue(wait_for(lambda: len(dict(master.getSystemState()[1]).get("/turtle1/cmd_vel", [])) >= 2,
                                 TIMEOUT_S), "the two relays do not subscribe /turtle1/cmd_vel")
        start = {ns: r.last for ns, r in poses.items()}
        one_shot = subprocess.run(COMMAND, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=30)
        self.assertEqual(one_shot.returncode, 0, one_shot.stdout)

        def moved():
            return [ns for ns in NAMESPACES if distance(poses[ns].last, start[ns]) > MOVED_M]
        self.assertTrue(wait_for(lambda: len(moved()) == 2, TIMEOUT_S),
                        "the one-shot Twist moved %s, not both turtles" % (moved() or "no turtle"))


if __name__ == "__main__":
    rospy.init_node("relay_two_turtles")
    rostest.rosrun("course_relay", "relay_two_turtles", RelayTwoTurtles)
