#!/usr/bin/env python3
"""Milestone `teleop` (001 2.1 Part A, #2.1.10): an executable of the text's package, run in a
terminal, starts the node mybot_teleop, publishes geometry_msgs/Twist on /turtle1/cmd_vel, and
its keys make turtle1 go forward, backward and turn left and right. The script name and the keys
are the student's: each executable is started until one publishes the topic (if none does, again
with the parameters of the student's turtlesim.launch: Part C may have made the topic a parameter),
and the key map is found by typing (see keymap.py, beside this check). Checks: courses/robotics_labs/milestones/teleop.md."""
import os

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_rospy import quick_exit
from course_format import causes
from course_milestones import students
import keyboard_probe as kp
from course_milestones import launch_files as lf
from course_milestones import guard
from course_milestones.discovery import publishes, topic_types
from course_milestones.milestone_case import MilestoneCase
from course_milestones.trusted import TURTLESIM
from course_checks.artifacts import save_canvas
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

TOPIC = "/turtle1/cmd_vel"
TURTLESIM_LAUNCH = "turtlesim.launch"


@guard.judged  # a violation of the trust policy fails the test, first
class TeleopMilestone(MilestoneCase):

    def load_turtlesim_launch_params(self, pkg):
        """Put the parameters of the student's turtlesim.launch on the server; whether there were any."""
        path, _ = lf.resolve(pkg, TURTLESIM_LAUNCH)
        try:
            found = lf.params(lf.load(path)) if path else {}
        except Exception:  # noqa: BLE001 - a launch file roslaunch cannot read adds nothing here
            return False
        for key, value in found.items():
            rospy.set_param(key, value)
        return bool(found)

    def test_keys_drive_turtle1(self):
        pkg = rospy.get_param("~pkg")
        poses = TopicRecorder("/turtle1/pose", Pose)
        commands = TopicRecorder(TOPIC, Twist)
        started = None
        try:
            self.assertTrue(wait_for(lambda: poses.last, 30),
                            causes.finding("course_tools", "turtlesim did not start (no /turtle1/pose)"))
            started, tried = students.start_registering(pkg, [], publishes(TOPIC), hint="teleop",
                                                        log_name=pkg)
            if started is None and self.load_turtlesim_launch_params(pkg):
                # Part C (#2.3.10) may have made the topic a parameter whose default is another topic
                # (the text's own solution defaults to cmd_vel): run it as the student's turtlesim.launch does.
                started, more = students.start_registering(pkg, [], publishes(TOPIC), hint="teleop",
                                                           log_name=pkg)
                tried += ["with the parameters of %s: %s" % (TURTLESIM_LAUNCH, m) for m in more]
            if started is None:
                self.fail(students.not_found_message(pkg, "publishes %s when run in a terminal (#2.1.10)" % TOPIC,
                                                     tried))
            node = started.registration.node
            self.assertTrue(node.startswith("/mybot_teleop"), causes.finding(
                "wrong_name", "%s publishes %s from a node named %s; #2.1.10 asks for a node named mybot_teleop "
                "(rospy.init_node('mybot_teleop'))" % (os.path.basename(started.path), TOPIC, node)))
            self.assertEqual(topic_types().get(TOPIC), "geometry_msgs/Twist",
                             causes.finding("wrong_type", "%s must carry geometry_msgs/Twist (#2.1.4)" % TOPIC))
            self.fail_on(kp.connect(commands, node))
            motion = kp.Motion(kp.turtle_pose(poses), "turtle1", min_distance=0.05, min_angle=0.05)
            result, problem = kp.discover_keymap(started.keyboard, commands, os.path.basename(started.path),
                                                 motion=motion)
            if problem:
                self.fail(problem)
        finally:
            if started is not None:
                started.keyboard.end()
            save_canvas()
            poses.unregister()
            commands.unregister()


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("teleop_check")
    guard.install([TURTLESIM])  # before any student code: believe only this simulator
    rostest.rosrun("course_milestones", "teleop", TeleopMilestone)
