#!/usr/bin/env python3
"""Milestone `chatter` (002 section 2): the example publisher sends text messages on /chatter_talk
and the example subscriber prints the messages it receives. The scripts are found by what they
register, so a script rosrun cannot run (no chmod +x) is named in the failure."""

import rospy
import rostest

from course_rospy import quick_exit
from course_format import causes
from course_milestones import messages, students
from course_milestones.discovery import script_hints, list_executables, topic_types
from course_milestones.milestone_case import MilestoneCase
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

TOPIC = "/chatter_talk"


def text_of(message) -> str:
    """The first string field of a message (std_msgs/String: data)."""
    for name, kind in zip(message.__slots__, message._slot_types):
        if kind == "string":
            return getattr(message, name)
    return str(message)


class ChatterMilestone(MilestoneCase):

    def test_publisher_and_subscriber(self):
        pkg = rospy.get_param("~pkg")
        paths = list_executables(pkg)
        self.assertTrue(paths, causes.finding(students.start_cause(pkg), "package %s has no executable scripts%s"
                                              % (pkg, script_hints(pkg))))
        started = [students.start(p) for p in paths]
        known = {}
        try:
            talker = students.find_role(started, lambda r: TOPIC in r.publishes, 25, known, settle=5.0)
            self.assertTrue(talker, students.role_missing("no executable in package %s publishes %s (%s)%s" % (
                pkg, TOPIC, students.describe(started, known), script_hints(pkg)), started, known, "publishes", pkg))
            listener = students.find_role(started, lambda r: TOPIC in r.subscribes, 15, known, settle=5.0)
            self.assertTrue(listener, students.role_missing("no executable in package %s subscribes to %s (%s)%s" % (
                pkg, TOPIC, students.describe(started, known), script_hints(pkg)), started, known, "subscribes", pkg))
            try:
                msg_class = messages.message_class(topic_types().get(TOPIC, ""))
            except messages.InterfaceError as err:
                self.fail(causes.finding(err.cause, "%s publishes on %s, but its type cannot be loaded: %s"
                                         % (talker.name, TOPIC, err)))
            heard = TopicRecorder(TOPIC, msg_class)
            # silent, unless what the talker printed says why (it registered, then died of Python 2
            # code: the check may or may not have seen its publisher before it went)
            self.assertTrue(wait_for(lambda: heard.count >= 2, 15), causes.finding(
                students.start_cause("", [students.output_of(talker.node)], default="silent"),
                "%s publishes nothing on %s" % (talker.name, TOPIC)))
            print("publisher: %s, subscriber: %s" % (talker.name, listener.name))

            def printed():
                output = listener.node.output()
                return any(text_of(m) and text_of(m) in output for m in heard.messages)
            self.assertTrue(wait_for(printed, 15), causes.finding(
                "not_printed", "%s printed none of the messages sent on %s, e.g. %r; its output ends with: %r"
                % (listener.name, TOPIC, text_of(heard.last), listener.node.output()[-300:])))
        finally:
            students.end_all(started)


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("chatter_check")
    rostest.rosrun("course_milestones", "chatter_check", ChatterMilestone)
