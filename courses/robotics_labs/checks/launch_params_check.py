#!/usr/bin/env python3
"""Milestone `launch_params` (001 2.3.1-2.3.7): `roslaunch mybot_teleop turtlesim.launch`, typed as
the text types it, starts turtlesim and the teleop node (#2.3.3), sets linear_scale and
angular_scale (#2.3.5, #2.3.6), and the keys in its terminal drive turtle1 (#2.3.2). Then the
launch file's teleop node is started again by itself, next to a fresh turtlesim, with both
parameters changed (x2 and x0.5): its commands must change by the same factors (#2.3.7: the node
reads the parameters and the command is scale x speed). Checks: courses/robotics_labs/milestones/launch_params.md."""
import os

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_rospy import quick_exit
from course_format import causes
from course_milestones import students
import keyboard_probe as kp
import keymap as km
from course_milestones import launch_files as lf
from course_milestones.discovery import publishes
from course_milestones.milestone_case import MilestoneCase
from course_checks.artifacts import artifact_path, save_canvas
from course_checks.nodes import NodeProcess
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

LAUNCH = "turtlesim.launch"
TOPIC = "/turtle1/cmd_vel"
SCALES = {"linear_scale": (km.FORWARD, 0, 2.0), "angular_scale": (km.LEFT, 1, 0.5)}  # direction, component, factor


class LaunchParamsMilestone(MilestoneCase):

    def setUp(self):
        self.pkg = rospy.get_param("~pkg")
        self.processes = []
        self.commands = TopicRecorder(TOPIC, Twist)
        self.poses = TopicRecorder("/turtle1/pose", Pose)

    def tearDown(self):
        while self.processes:
            self.processes.pop().end()
        self.commands.unregister()
        self.poses.unregister()

    def motion(self):
        return kp.Motion(kp.turtle_pose(self.poses), "turtle1", min_distance=0.05, min_angle=0.05)

    def test_launch_file_and_parameters(self):
        path, reason = lf.resolve(self.pkg, LAUNCH)
        if path is None:
            self.fail(causes.finding("not_started", "`roslaunch %s %s` finds no launch file (#2.3.1 puts it in the "
                                     "launch folder of %s): %s" % (self.pkg, LAUNCH, self.pkg, reason)))
        try:
            config = lf.load(path)
        except lf.LaunchFileError as err:
            self.fail(causes.finding("wrong_launch", str(err)))
        scales = {name: lf.params_named(config, name) for name in SCALES}
        for name, found in scales.items():
            self.assertTrue(found, causes.finding("wrong_launch", "%s sets no parameter %s (#2.3.5 asks for <param "
                                                  "name=\"%s\" value=\"1.0\"/>)" % (LAUNCH, name, name)))
            for key, value in found.items():
                self.assertTrue(isinstance(value, (int, float)) and value > 0, causes.finding(
                    "wrong_value", "%s sets %s to %r; #2.3.5 asks for a number (1.0)" % (LAUNCH, key, value)))

        # Phase 1: the launch file as the text runs it.
        launch = students.Roslaunch(self.pkg, LAUNCH, "roslaunch_" + LAUNCH)
        self.processes.append(launch)
        self.assertTrue(wait_for(lambda: self.poses.last or not launch.node.running(), 40) and self.poses.last,
                        causes.finding("wrong_launch", "`roslaunch %s %s` started no turtlesim (no /turtle1/pose; "
                                       "#2.3.3 asks the launch file to start turtlesim_node too)" % (self.pkg, LAUNCH)))
        teleop = students.wait_for_publisher(TOPIC, launch)
        self.assertIsNotNone(teleop, causes.finding("wrong_launch", "`roslaunch %s %s` started no node publishing %s "
                                                    "(#2.3.1)" % (self.pkg, LAUNCH, TOPIC)))
        for found in scales.values():
            for key in found:
                self.assertTrue(rospy.has_param(key), causes.finding("wrong_launch", "%s is not on the parameter "
                                                                     "server (#2.3.6)" % key))
        self.fail_on(kp.connect(self.commands, teleop.node))
        result, problem = kp.discover_keymap(launch, self.commands, "%s (%s)" % (teleop.node, LAUNCH),
                                             motion=self.motion())
        if problem:
            self.fail(causes.finding(causes.of(problem, "not_moving"), "with `roslaunch %s %s`: %s"
                                     % (self.pkg, LAUNCH, problem)))
        save_canvas()
        self.processes.remove(launch)
        launch.stop()

        # Phase 2: the same node, parameters changed on the server, started again by itself.
        node = lf.node_named(config, teleop.node)
        self.assertIsNotNone(node, causes.finding("wrong_launch", "the node %s publishing %s is not one of %s's nodes"
                                                  % (teleop.node, TOPIC, LAUNCH)))
        changed = []
        for name, (_, _, factor) in SCALES.items():
            for key, value in scales[name].items():
                rospy.set_param(key, value * factor)
                changed.append("%s=%g" % (key, value * factor))
        changed = ", ".join(changed)
        self.poses.clear()
        self.processes.append(NodeProcess.rosrun("turtlesim", "turtlesim_node", log_path=artifact_path("turtlesim")))
        self.assertTrue(wait_for(lambda: self.poses.last, 30),
                        causes.finding("course_tools", "turtlesim did not start again"))
        command, env = lf.node_command(node)
        again, registered, _ = students.start_and_wait(command, publishes(TOPIC), node.type + "_rescaled",
                                                       env=dict(os.environ, **env))
        self.processes.append(again)
        self.assertIsNotNone(registered, causes.finding("not_published", "%s, started again with %s, publishes no %s"
                                                        % (node.type, changed, TOPIC)))
        self.fail_on(kp.connect(self.commands, registered.node))
        rescaled, problem = kp.discover_keymap(again, self.commands, "%s (rescaled)" % registered.node,
                                               first=result.keymap)
        if problem:
            self.fail(causes.finding(causes.of(problem, "not_moving"), "with %s: %s" % (changed, problem)))
        for name, (direction, index, factor) in SCALES.items():
            was, got = result.commands[direction][index], rescaled.commands[direction][index]
            self.assertTrue(km.scaled(was, got, factor), causes.finding(
                "param_ignored", "the node ignores %s: with %s x%g (%s), pressing %s sent %s = %g instead of %g (it "
                "was %g with the launch file's value); #2.3.7 asks the node to read %s from the parameter server and "
                "scale its command with it" % (name, name, factor, changed,
                                               km.key_label(rescaled.keymap.keys[direction], rescaled.keymap.enter),
                                               km.EXPECTED[direction].split()[0], got, was * factor, was, name)))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("launch_params_check")
    rostest.rosrun("course_milestones", "launch_params", LaunchParamsMilestone)
