#!/usr/bin/env python3
"""Lab 2 checkpoint 3: with turtle2 and turtle3 spawned and the server started (with the turtle
names as arguments, as the text suggests), /<turtle>/patrol vel omega x y theta puts each turtle
at its pose and keeps it circling; a bad request fails and the server keeps serving."""
import math
import unittest

import rospy
import rostest
from turtlesim.msg import Pose
from turtlesim.srv import Spawn

from course_testkit.nodes import NodeProcess
from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for
from turtle_patrol.srv import Patrol

REQUESTS = {"turtle1": (1.0, 1.0, 3.0, 3.0, 0.0), "turtle2": (1.5, -1.0, 8.0, 8.0, 1.57),
            "turtle3": (2.0, 1.5, 3.0, 8.0, -1.0)}


class PatrolMilestone(unittest.TestCase):
    def test_turtles_patrol_from_their_poses(self):
        rospy.wait_for_service("/spawn", 30)
        spawn = rospy.ServiceProxy("/spawn", Spawn)
        spawn(2.0, 2.0, 0.0, "turtle2")
        spawn(9.0, 2.0, 0.0, "turtle3")
        server = NodeProcess.rosrun(rospy.get_param("~node_pkg"), rospy.get_param("~node_type"),
                                    list(REQUESTS))
        poses = {t: TopicRecorder("/%s/pose" % t, Pose) for t in REQUESTS}
        try:
            for turtle, req in REQUESTS.items():
                rospy.wait_for_service("/%s/patrol" % turtle, 30)
                response = rospy.ServiceProxy("/%s/patrol" % turtle, Patrol)(*req)
                self.assertAlmostEqual(response.cmd.linear.x, req[0], places=4)
                self.assertAlmostEqual(response.cmd.angular.z, req[1], places=4)
                # turtlesim applies a teleport at its next tick: a pose at the requested start follows
                def at_start(t=turtle, r=req):
                    return any(math.hypot(p.x - r[2], p.y - r[3]) < 0.3 for p in poses[t].messages[-20:])
                self.assertTrue(wait_for(at_start, 5),
                                "%s did not start at (%.1f, %.1f)" % (turtle, req[2], req[3]))
            for turtle, req in REQUESTS.items():
                poses[turtle].clear()
            rospy.sleep(2.5)  # observe the patrol (more than the 1 s turtlesim command timeout)
            for turtle, (vel, omega, x, y, _) in REQUESTS.items():
                recent = poses[turtle].messages
                self.assertGreater(len(recent), 50)
                self.assertTrue(all(abs(p.linear_velocity - vel) < 1e-3 and abs(p.angular_velocity - omega) < 1e-3
                                    for p in recent[-30:]), "%s is not circling at the requested speed" % turtle)
                radius = abs(vel / omega)
                # every pose stays on a circle of radius vel/omega: within the diameter of the start
                self.assertLess(max(math.hypot(p.x - x, p.y - y) for p in recent), 2 * radius + 0.3)
            with self.assertRaises(rospy.ServiceException):
                rospy.ServiceProxy("/turtle1/patrol", Patrol)(1.0, 1.0, float("nan"), 3.0, 0.0)
            self.assertTrue(server.running(), "a bad request killed the server")
        finally:
            server.stop()


if __name__ == "__main__":
    rospy.init_node("milestone_patrol")
    rostest.rosrun("turtle_patrol", "milestone_patrol", PatrolMilestone)
