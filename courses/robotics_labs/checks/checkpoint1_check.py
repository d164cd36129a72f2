#!/usr/bin/env python3
"""Milestone `checkpoint1` (002 section 3, checkpoint 1): in package my_chatter, a publisher
prompts for lines of text and publishes each with the time it was entered on /user_messages as a
TimestampString (one string, one number); a subscriber prints each message as
`Message: <message>, Sent at: <timestamp>, Received at: <timestamp>`.

The scripts and the message's field names are the student's: the scripts are found by what they
register, the fields by their types in the message class the publisher declares on the master."""
import time

import rospy
import rostest

from course_rospy import quick_exit
from course_format import causes
from course_milestones import messages, students
import closest_line
import timestamped
from course_milestones.discovery import script_hints, list_executables, topic_types, unbuilt_problems
from course_milestones.milestone_case import MilestoneCase
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

TOPIC = "/user_messages"
TYPE_NAME = "TimestampString"
LINES = ("hello turtle", "second line")
PROBE = "a probe sent 100 s ago"


class CheckpointOne(MilestoneCase):

    def setUp(self):
        self.pkg = rospy.get_param("~pkg")
        paths = list_executables(self.pkg)
        self.assertTrue(paths, causes.finding(students.start_cause(self.pkg), "package %s has no executable scripts%s"
                                              % (self.pkg, script_hints(self.pkg))))
        self.started = [students.start(p) for p in paths]
        self.known = {}

    def tearDown(self):
        students.end_all(getattr(self, "started", []))

    def find(self, what: str, condition):
        found = students.find_role(self.started, condition, 25, self.known, settle=5.0)
        if not found:  # a message the package never built comes first: it is the cause to fix
            unbuilt = unbuilt_problems(self.pkg)
            missing = "no executable in package %s %s %s (%s)%s" % (
                self.pkg, what, TOPIC, students.describe(self.started, self.known), script_hints(self.pkg))
            if unbuilt:  # the first problem's cause leads
                self.fail(causes.finding(causes.of(unbuilt[0], causes.CHECK_FAILED), "\n".join(unbuilt + [missing])))
            self.fail(students.role_missing(missing, self.started, self.known, what.split()[0], self.pkg))
        return found

    def type_line(self, text: str) -> float:
        self.assertTrue(self.talker.node.running(), causes.finding(  # a line of it arrived: it did some of it
            causes.exited(bool(self.heard.messages)), "%s exited while reading lines; its output ends with: %r"
            % (self.talker.name, self.talker.node.output()[-300:])))
        stdin = self.talker.node.proc.stdin
        typed_at = time.time()
        stdin.write((text + "\n").encode())
        stdin.flush()
        return typed_at

    def arrived(self, text: str):
        return next((m for m in reversed(self.heard.messages) if getattr(m, self.fields.text).strip() == text), None)

    def stamp_seconds(self, message, near: float) -> float:
        value = getattr(message, self.fields.time)
        if self.fields.time_type == "time":
            return value.to_sec()
        return timestamped.as_seconds(float(value), near)

    def test_typed_lines_are_published_and_printed(self):
        self.talker = self.find("publishes", lambda r: TOPIC in r.publishes)
        listener = self.find("subscribes to", lambda r: TOPIC in r.subscribes)
        print("publisher: %s, subscriber: %s" % (self.talker.name, listener.name))
        msg_type = topic_types()[TOPIC]
        self.assertEqual(msg_type.split("/")[-1], TYPE_NAME, causes.finding(
            "wrong_type", "%s publishes %s on %s: the text's message type is %s"
            % (self.talker.name, msg_type, TOPIC, TYPE_NAME)))
        try:
            msg_class = messages.message_class(msg_type)
        except messages.InterfaceError as err:
            self.fail(causes.finding(err.cause, "cannot load the message class %s: %s" % (msg_type, err)))
        self.fields, problem = timestamped.find_fields(msg_class.__slots__, msg_class._slot_types)
        self.assertFalse(problem, causes.finding("wrong_type", "%s: %s" % (msg_type, problem)))
        print("fields: text in %r, time in %r (%s)" % (self.fields.text, self.fields.time, self.fields.time_type))
        self.heard = TopicRecorder(TOPIC, msg_class)

        # Warm up until a typed line reaches both us and the student's subscriber (a line published
        # before a subscriber has connected is lost, for every publisher).
        def warmed_up():
            return self.arrived("warm up") and "warm up" in listener.node.output()
        for _ in range(12):
            self.type_line("warm up")
            if wait_for(warmed_up, 1.0):
                break
        self.assertTrue(self.arrived("warm up"), causes.finding(
            "silent", "lines typed into %s never arrived on %s; its output ends with: %r"
            % (self.talker.name, TOPIC, self.talker.node.output()[-300:])))
        self.assertTrue(wait_for(warmed_up, 5), causes.finding(
            "not_printed", "%s printed nothing when lines arrived on %s; its output: %r"
            % (listener.name, TOPIC, listener.node.output()[-300:])))

        stamps = []
        for i, line in enumerate(LINES):
            if i:
                time.sleep(1.0)  # the time a line is entered, not the time its prompt was shown
            typed_at = self.type_line(line)
            message = wait_for(lambda: self.arrived(line), 10)
            received_at = time.time()
            self.assertTrue(message, causes.finding(
                "wrong_value", "typed %r into %s, but no message with that text arrived on %s (got: %s)"
                % (line, self.talker.name, TOPIC, [getattr(m, self.fields.text) for m in self.heard.messages][-4:])))
            stamp = self.stamp_seconds(message, typed_at)
            hint = " (a float32 cannot hold rospy.get_time() to the second: the text asks for float64)" \
                if self.fields.time_type == "float32" else ""
            self.assertTrue(timestamped.entered_in_time(stamp, typed_at, received_at,
                                                        self.fields.time_type.startswith(("int", "uint"))),
                            causes.finding("wrong_value", "the line %r was entered at %.3f but its %s field says %r: "
                                           "it should be the time the line was entered (e.g. rospy.get_time() right "
                                           "after reading it)%s" % (line, typed_at, self.fields.time,
                                                                    getattr(message, self.fields.time), hint)))
            stamps.append(stamp)
        said = self.talker.node.output()
        prompts = timestamped.prompt_count(said)
        if prompts < 2:
            self.fail(causes.finding("not_printed", "%s should prompt %r before every line; it prompted %d times%s; "
                                     "its output: %r" % (self.talker.name, timestamped.PROMPT, prompts,
                                                         "" if prompts else closest_line.closest_words(
                                                             said, timestamped.PROMPT_FORM), said[-300:])))

        wait_for(lambda: LINES[-1] in listener.node.output(), 10)
        printed = wait_for(lambda: timestamped.line_for(listener.node.output(), LINES[-1]), 1.0)
        if not printed:
            said = listener.node.output()
            self.fail(causes.finding(
                "not_printed", "%s did not print %r in the text's format '%s'%s; its output ends with: %r" % (
                    listener.name, LINES[-1], timestamped.FORM.display,
                    closest_line.closest_words(said, timestamped.printed_form(LINES[-1])), said[-400:])))
        self.assertTrue(timestamped.time_matches(printed.sent, stamps[-1]), causes.finding(
            "wrong_value", "%s printed 'Sent at: %s' for %r, whose timestamp is %.6f" % (
                listener.name, printed.sent, LINES[-1], stamps[-1])))
        self.check_probe(listener, msg_class)

    def check_probe(self, listener, msg_class):
        """A message we send with an old timestamp: Sent at must show it, Received at the arrival."""
        sent_at = round(time.time() - 100.0, 2)
        probe = msg_class()
        setattr(probe, self.fields.text, PROBE)
        kind = self.fields.time_type
        setattr(probe, self.fields.time, rospy.Time.from_sec(sent_at) if kind == "time"
                else int(sent_at) if kind.startswith(("int", "uint")) else sent_at)
        publisher = rospy.Publisher(TOPIC, msg_class, queue_size=1, latch=True)
        published_at = time.time()
        publisher.publish(probe)
        line = wait_for(lambda: timestamped.line_for(listener.node.output(), PROBE), 10)
        self.assertTrue(line, causes.finding(
            "not_printed", "%s printed nothing for a message sent on %s by another node; its output ends with: %r"
            % (listener.name, TOPIC, listener.node.output()[-300:])))
        expected = float(int(sent_at)) if kind.startswith(("int", "uint")) else sent_at
        self.assertTrue(timestamped.time_matches(line.sent, expected),
                        causes.finding("wrong_value", "%s printed 'Sent at: %s' for a message whose timestamp is "
                                       "%.2f: Sent at is the time in the message" % (listener.name, line.sent,
                                                                                      expected)))
        received = timestamped.as_seconds(float(line.received), published_at)
        self.assertTrue(published_at - 0.5 <= received <= time.time() + 0.5,
                        causes.finding("wrong_value", "%s printed 'Received at: %s' for a message that arrived at "
                                       "about %.2f: Received at is the subscriber's clock when the message arrives"
                                       % (listener.name, line.received, published_at)))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("checkpoint1_check")
    rostest.rosrun("course_milestones", "checkpoint1_check", CheckpointOne)
