#!/usr/bin/env python3
"""Milestone `checkpoint2` (002 section 4, checkpoint 2): an executable of lab2_turtlesim, run in a
terminal with a turtle's name as its argument (`rosrun lab2_turtlesim turtle_controller.py turtle1`),
publishes geometry_msgs/Twist on /<name>/cmd_vel, and its keys (single keys or raw_input() lines:
the text allows both) make that turtle go forward, backward and turn left and right. A second
controller, started for a spawned turtle with another name while the first still runs, drives
only its own turtle (checkpoint 2: "controlling two turtles with different inputs").
Checks: courses/robotics_labs/milestones/checkpoint2.md."""
import os

import rospy
import rostest
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose
from turtlesim.srv import Spawn

from course_rospy import quick_exit
from course_format import causes
from course_milestones import students
import keyboard_probe as kp
import keymap as km
from course_milestones import guard
from course_milestones.discovery import node_uris, publishes, topic_types
from course_milestones.milestone_case import MilestoneCase
from course_milestones.trusted import TURTLESIM
from course_checks.artifacts import save_canvas
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

FIRST, SECOND = "turtle1", "leo"   # the second turtle's name is not turtleN: any name must work
SECOND_POSE = (2.0, 2.0, 0.0)


def new_commands(recorder, mark):
    """The distinct (linear.x, angular.z) commands after index `mark` other than the one before it: a
    controller that publishes all the time repeats its last command, which is not a new one."""
    messages = recorder.messages
    last = (messages[mark - 1].linear.x, messages[mark - 1].angular.z) if mark else None
    return sorted({(m.linear.x, m.angular.z) for m in messages[mark:]} - {last})


@guard.judged  # a violation of the trust policy fails the test, first
class Checkpoint2Milestone(MilestoneCase):

    def setUp(self):
        self.pkg = rospy.get_param("~pkg")
        self.keyboards = []
        self.poses = {t: TopicRecorder("/%s/pose" % t, Pose) for t in (FIRST, SECOND)}
        self.commands = {t: TopicRecorder("/%s/cmd_vel" % t, Twist) for t in (FIRST, SECOND)}

    def tearDown(self):
        for keyboard in self.keyboards:
            keyboard.end()
        save_canvas()
        for recorder in list(self.poses.values()) + list(self.commands.values()):
            recorder.unregister()

    def motion(self, turtle):
        return kp.Motion(kp.turtle_pose(self.poses[turtle]), turtle, min_distance=0.05, min_angle=0.05)

    def test_two_controllers_two_turtles(self):
        self.assertTrue(wait_for(lambda: self.poses[FIRST].last, 30),
                        causes.finding("course_tools", "turtlesim did not start (no /turtle1/pose)"))
        rospy.wait_for_service("/spawn", 30)
        rospy.ServiceProxy("/spawn", Spawn)(*SECOND_POSE, SECOND)
        topic = "/%s/cmd_vel" % FIRST
        started, tried = students.start_registering(self.pkg, [FIRST], publishes(topic), hint="control|teleop|key",
                                                    log_name="controller_" + FIRST)
        if started is None:
            self.fail(students.not_found_message(
                self.pkg, "publishes %s when run as `rosrun %s SCRIPT %s` in a terminal" % (topic, self.pkg, FIRST),
                tried))
        self.keyboards.append(started.keyboard)
        script = os.path.basename(started.path)
        self.assertEqual(topic_types().get(topic), "geometry_msgs/Twist", causes.finding(
            "wrong_type", "%s must carry geometry_msgs/Twist, the type turtlesim reads (rostopic type %s)"
            % (topic, topic)))
        self.fail_on(kp.connect(self.commands[FIRST], started.registration.node))
        result, problem = kp.discover_keymap(started.keyboard, self.commands[FIRST], "%s %s" % (script, FIRST),
                                             motion=self.motion(FIRST))
        if problem:
            self.fail(causes.finding(causes.of(problem, "not_moving"), "`rosrun %s %s %s`: %s"
                                     % (self.pkg, script, FIRST, problem)))

        # A second controller, for the other turtle, while the first one runs.
        first_uri = node_uris().get(started.registration.node)
        topic2 = "/%s/cmd_vel" % SECOND
        second, registered, seen = students.start_and_wait([started.path, SECOND], publishes(topic2),
                                                           "controller_" + SECOND, timeout=20)
        self.keyboards.append(second)
        if registered is None:
            published = sorted({t for r in seen for t in r.publishes if t.endswith("/cmd_vel")})
            self.fail(causes.finding("wrong_topic" if published else "not_published",
                                     "`rosrun %s %s %s` publishes no %s (it publishes %s): the controller must drive "
                                     "the turtle named on its command line" % (self.pkg, script, SECOND, topic2,
                                                                              ", ".join(published) or "nothing")))
        self.assertTrue(started.keyboard.node.running() and node_uris().get(started.registration.node) == first_uri,
                        causes.finding("node_exited", "starting a second controller (`%s %s`) shut down the first "
                                       "(`%s %s`, node %s): two nodes cannot have the same name; give each its own "
                                       "(e.g. anonymous=True or the turtle's name)"
                                       % (script, SECOND, script, FIRST, started.registration.node)))
        self.fail_on(kp.connect(self.commands[SECOND], registered.node))
        # different inputs: the second turtle's keyboard drives it (and only it), then a left turn on the first's
        mark = self.commands[FIRST].count
        _, problem = kp.discover_keymap(second, self.commands[SECOND], "%s %s" % (script, SECOND),
                                        first=result.keymap, motion=self.motion(SECOND))
        if problem:
            self.fail(causes.finding(causes.of(problem, "not_moving"), "`rosrun %s %s %s`: %s"
                                     % (self.pkg, script, SECOND, problem)))
        self.assertFalse(new_commands(self.commands[FIRST], mark), causes.finding(
            "wrong_topic", "keys typed into the %s controller also sent commands to %s: %s"
            % (SECOND, FIRST, new_commands(self.commands[FIRST], mark))))
        mark = self.commands[SECOND].count
        left, enter = result.keymap.keys[km.LEFT], result.keymap.enter
        self.assertTrue(started.keyboard.press_until(left, lambda: any(km.answers(km.LEFT, m.linear.x, m.angular.z)
                                                                       for m in self.commands[FIRST].messages),
                                                     tries=3, interval=kp.PROBE_WINDOW, enter=enter),
                        causes.finding("not_moving", "after the %s controller started, %s in the %s controller's "
                                       "terminal sent %s no left turn" % (SECOND, km.key_label(left, enter), FIRST,
                                                                          FIRST)))
        self.assertFalse(new_commands(self.commands[SECOND], mark), causes.finding(
            "wrong_topic", "keys typed into the %s controller also sent commands to %s: %s"
            % (FIRST, SECOND, new_commands(self.commands[SECOND], mark))))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("checkpoint2_check")
    guard.install([TURTLESIM])  # before any student code: believe only this simulator
    rostest.rosrun("course_milestones", "checkpoint2", Checkpoint2Milestone)
