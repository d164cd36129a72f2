#!/usr/bin/env python3
"""Milestone `turtlebot` (001 2.3.8-2.3.12): the teleop node drives the simulated TurtleBot3 Burger.

1. #2.3.8-#2.3.11: with the course's simulator running (`roslaunch turtlebot3_gazebo
   turtlebot3_empty_world.launch`), `roslaunch mybot_teleop turtlebot.launch` starts the teleop,
   which takes its topic from a parameter the launch file sets to cmd_vel; its keys drive the Burger
   (/odom) forward, backward and both ways round, with commands the Burger can do (0.22 m/s,
   2.84 rad/s: the "appropriate values" of the scales).
2. #2.3.12: `roslaunch mybot_teleop turtlebot3_empty_world.launch` alone starts the simulator, the
   Burger and the teleop, whose keys drive the Burger the same way.
Both launch files run exactly as the text types them, in the TurtleBot3 environment the course's
machines have (TURTLEBOT3_MODEL=burger, which the text's own turtlebot3_empty_world.launch reads
with $(env TURTLEBOT3_MODEL)). Checks: courses/robotics_labs/milestones/turtlebot.md."""
import os

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from course_rospy import quick_exit
from course_format import causes
from course_milestones import students
import keyboard_probe as kp
import keymap as km
from course_milestones import launch_files as lf
from course_milestones.discovery import MASTER_POLL_S, system_state
from course_milestones.milestone_case import MilestoneCase
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for
from mujoco_gazebo.engine.diffdrive import DiffDriveGeometry

TOPIC = "/cmd_vel"
BURGER = DiffDriveGeometry()
SIM_TIMEOUT = 60.0
TURTLEBOT3_ENV = {"TURTLEBOT3_MODEL": "burger"}  # set on the course's machines by the TurtleBot3 setup


class TurtlebotMilestone(MilestoneCase):

    def setUp(self):
        self.pkg = rospy.get_param("~pkg")
        self.processes = []
        self.commands = TopicRecorder(TOPIC, Twist)
        self.odom = TopicRecorder("/odom", Odometry)

    def tearDown(self):
        while self.processes:
            self.processes.pop().end()
        self.commands.unregister()
        self.odom.unregister()

    def stop_all(self):
        while self.processes:
            self.processes.pop().stop()

    def resolve(self, name, step):
        path, reason = lf.resolve(self.pkg, name)
        if path is None:
            self.fail(causes.finding("not_started", "`roslaunch %s %s` finds no launch file (%s): %s"
                                     % (self.pkg, name, step, reason)))
        try:
            return lf.load(path)
        except lf.LaunchFileError as err:
            self.fail(causes.finding("wrong_launch", str(err)))

    def drive(self, keyboard, launch_name, first=None):
        """Find the teleop publishing /cmd_vel and its keys; each key must move the Burger, with a
        command the Burger can do."""
        teleop = students.wait_for_publisher(TOPIC, keyboard)
        self.assertIsNotNone(teleop, causes.finding(
            "wrong_launch", "`roslaunch %s %s` started no node publishing %s (#2.3.10 asks the teleop to take its "
            "topic from a parameter set to cmd_vel)" % (self.pkg, launch_name, TOPIC)))
        self.fail_on(kp.connect(self.commands, teleop.node))
        motion = kp.Motion(kp.odom_pose(self.odom), "the Burger", min_distance=0.01, min_angle=0.03, interval=3.0)
        result, problem = kp.discover_keymap(keyboard, self.commands, "%s (%s)" % (teleop.node, launch_name),
                                             first=first, motion=motion)
        if problem:
            self.fail(causes.finding(causes.of(problem, "not_moving"), "with `roslaunch %s %s`: %s (on /odom)"
                                     % (self.pkg, launch_name, problem)))
        for direction, command in result.commands.items():
            linear, angular = command.linear_x, command.angular_z
            self.assertTrue(abs(linear) <= BURGER.max_linear + 1e-6 and abs(angular) <= BURGER.max_angular + 1e-6,
                            causes.finding("wrong_value", "with `roslaunch %s %s`, %s sends linear.x=%g angular.z=%g: "
                                           "the Burger goes at most %g m/s and %g rad/s; #2.3.11 asks for "
                                           "linear_scale and angular_scale values that suit it"
                                           % (self.pkg, launch_name, km.key_label(result.keymap.keys[direction],
                                                                                  result.keymap.enter),
                                              linear, angular, BURGER.max_linear, BURGER.max_angular)))
        return result.keymap

    def wait_for_odom(self, process, what, cause):
        """Wait for /odom from `process`'s simulator; else fail with `cause` (whose simulator it is)."""
        self.odom.clear()
        self.assertTrue(wait_for(lambda: self.odom.last or not process.node.running(), SIM_TIMEOUT)
                        and self.odom.last, causes.finding(
                            cause, "%s: no /odom, the simulator did not start or no Burger was spawned" % what))

    def test_teleop_drives_the_burger(self):
        config = self.resolve("turtlebot.launch", "#2.3.10 asks for a new launch file turtlebot.launch")
        for name in ("linear_scale", "angular_scale"):
            self.assertTrue(lf.params_named(config, name),
                            causes.finding("wrong_launch", "turtlebot.launch sets no parameter %s (#2.3.11)" % name))
        self.assertTrue(lf.params_with_value(config, ("cmd_vel", "/cmd_vel")), causes.finding(
            "wrong_launch", "turtlebot.launch sets no parameter to the topic cmd_vel (#2.3.10: the topic name comes "
            "from a parameter set in turtlebot.launch)"))
        self.resolve("turtlebot3_empty_world.launch", "#2.3.12 asks for your own turtlebot3_empty_world.launch")

        sim = students.Roslaunch("turtlebot3_gazebo", "turtlebot3_empty_world.launch", "simulator", ["gui:=false"],
                                 student=False)
        self.processes.append(sim)
        self.wait_for_odom(sim, "`roslaunch turtlebot3_gazebo turtlebot3_empty_world.launch`", "course_tools")
        teleop = students.Roslaunch(self.pkg, "turtlebot.launch", "roslaunch_turtlebot.launch")
        self.processes.append(teleop)
        keys = self.drive(teleop, "turtlebot.launch")
        self.stop_all()
        # the course's simulator must be gone before the student's own starts
        self.assertTrue(wait_for(lambda: not any("/odom" in r.publishes for r in system_state().values()), 15,
                                 MASTER_POLL_S),
                        causes.finding("course_tools", "the course's simulator did not stop"))

        world = students.Roslaunch(self.pkg, "turtlebot3_empty_world.launch",
                                      "roslaunch_turtlebot3_empty_world.launch")
        self.processes.append(world)
        self.wait_for_odom(world, "`roslaunch %s turtlebot3_empty_world.launch` (#2.3.12)" % self.pkg, "wrong_launch")
        self.drive(world, "turtlebot3_empty_world.launch", first=keys)


if __name__ == "__main__":
    for variable, value in TURTLEBOT3_ENV.items():
        os.environ.setdefault(variable, value)  # inherited by every launch this check starts
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("turtlebot_check")
    rostest.rosrun("course_milestones", "turtlebot", TurtlebotMilestone)
