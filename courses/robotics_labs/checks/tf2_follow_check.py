#!/usr/bin/env python3
"""Milestone `tf2_follow` (004 10, sections 5-9): `roslaunch pkg_tf turtle_following.launch` (the ROS 1
form of turtle_following.launch.py) starts turtlesim, a turtle_tf_broadcaster per turtle (frame
world -> turtleN from /turtleN/pose), and turtle_following, which spawns turtle2 at (4, 2) and
steers it toward turtle1 through tf2 "until they overlap".

turtle1 is moved to a corner first (the text drives it with the teleop), so a follower that
heads for turtle1's start instead of its frame does not pass.
"""
import math

import rospy
import rostest
import tf2_ros
from turtlesim.msg import Pose
from turtlesim.srv import TeleportAbsolute

from course_rospy import quick_exit
from course_format import causes
from course_milestones import discovery
from course_milestones import launch_files as lf
from course_milestones.milestone_case import MilestoneCase
from course_milestones.students import Roslaunch
from course_checks.artifacts import save_canvas
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

LAUNCH_FILE = "turtle_following.launch"
SPAWN_AT = (4.0, 2.0)
LEADER_AT = (8.5, 8.5)
CAUGHT = 1.0  # m: "follow them until they overlap" (a turtle is ~1 m wide on the canvas)
FOLLOW_TIMEOUT = 25.0  # s; the text's follower publishes once a second and catches up in ~10 s


class Tf2FollowMilestone(MilestoneCase):
    launch = None

    @classmethod
    def setUpClass(cls):
        cls.pkg = rospy.get_param("~pkg")
        cls.buffer = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buffer)
        cls.poses = {name: TopicRecorder("/%s/pose" % name, Pose) for name in ("turtle1", "turtle2")}
        cls.problem = lf.missing_launch_file(cls.pkg, LAUNCH_FILE)
        if cls.problem:
            return
        cls.launch = Roslaunch(cls.pkg, LAUNCH_FILE, "roslaunch_turtle_following")
        if not wait_for(lambda: cls.poses["turtle1"].last, 30):
            cls.problem = causes.finding("wrong_launch", "`roslaunch %s %s` started no turtlesim (no /turtle1/pose)"
                                         % (cls.pkg, LAUNCH_FILE))
        elif not wait_for(lambda: cls.poses["turtle2"].last, 20):
            cls.problem = causes.finding("wrong_launch", "turtle_following did not spawn turtle2 (no /turtle2/pose): "
                                                         "call the spawn service")

    @classmethod
    def tearDownClass(cls):
        simulator = [n for n, r in discovery.system_state().items() if "/turtle1/pose" in r.publishes]
        if simulator:
            save_canvas(simulator[0] + "/snapshot")
        if cls.launch is not None:
            cls.launch.end()

    def setUp(self):
        self.assertFalse(self.problem, self.problem)

    def frame(self, child):
        try:
            return self.buffer.lookup_transform("world", child, rospy.Time(0), rospy.Duration(5.0)).transform
        except tf2_ros.TransformException:
            return None

    def test_1_turtle2_spawned_at_4_2(self):
        first = self.poses["turtle2"].messages[0]
        self.assertTrue(math.hypot(first.x - SPAWN_AT[0], first.y - SPAWN_AT[1]) < 1.0,
                        causes.finding("wrong_value", "turtle2 first seen at (%.2f, %.2f); the text spawns it at "
                                       "(4, 2)" % (first.x, first.y)))

    def test_2_broadcasters_publish_world_frames(self):
        for name in ("turtle1", "turtle2"):
            seen = self.frame(name)
            self.assertTrue(seen is not None, causes.finding(
                "no_frame", "no transform world -> %s on /tf: run turtle_tf_broadcaster with turtlename %s"
                % (name, name)))
            pose = self.poses[name].last
            self.assertTrue(math.hypot(seen.translation.x - pose.x, seen.translation.y - pose.y) < 0.3,
                            causes.finding("wrong_value", "world -> %s is at (%.2f, %.2f) but /%s/pose says "
                                           "(%.2f, %.2f)" % (name, seen.translation.x, seen.translation.y, name,
                                                             pose.x, pose.y)))

    def test_3_turtle2_follows_turtle1(self):
        rospy.wait_for_service("/turtle1/teleport_absolute", 10)
        rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)(LEADER_AT[0], LEADER_AT[1], 0.0)

        def distance():
            a, b = self.poses["turtle1"].last, self.poses["turtle2"].last
            return math.hypot(a.x - b.x, a.y - b.y)
        wait_for(lambda: math.hypot(self.poses["turtle1"].last.x - LEADER_AT[0],
                                    self.poses["turtle1"].last.y - LEADER_AT[1]) < 0.01, 5)
        start = distance()
        caught = wait_for(lambda: distance() < CAUGHT, FOLLOW_TIMEOUT, interval=0.1)
        self.assertTrue(caught, causes.finding(
            "not_moving", "turtle2 stayed %.2f m from turtle1 after %.0f s (it started %.2f m away): turtle_following "
            "should steer turtle2 toward the frame turtle1" % (distance(), FOLLOW_TIMEOUT, start)))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("tf2_follow_check")
    rostest.rosrun("course_milestones", "tf2_follow", Tf2FollowMilestone)
