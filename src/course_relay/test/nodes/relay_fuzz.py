#!/usr/bin/env python3
"""Fuzzing the relay with hypothesis, through its topics and its command line.

- Payloads: random Strings, Twists (huge, NaN, inf) and Float64MultiArrays come out of OUT
  byte for byte as they went into IN.
- Type switching: /fuzz/switch_in gets Strings first, then Float64s and Twists too; only the
  Strings come out, and the relay warns about each other type, naming both.
- Names: `relay IN OUT` with random names either relays (valid names) or exits promptly,
  non-zero, saying which name is not valid; it never hangs.
"""
import io
import os
import tempfile
import time
import unittest

import rosgraph.names
import rospy
import rostest
from geometry_msgs.msg import Twist, Vector3
from hypothesis import HealthCheck, Phase, assume, given, settings, strategies as st
from rosgraph_msgs.msg import Log
from std_msgs.msg import Float64, Float64MultiArray, String

from course_relay.names import topic_name_problem
from course_testkit.fuzz import valid_names, wild_floats, wild_names
from course_checks.nodes import NodeProcess
from course_checks.recorders import RosoutRecorder, TopicRecorder
from course_checks.waiting import wait_for

TIMEOUT_S = 20
EXIT_S = 10  # an invalid name must end the relay within this (a hang is the bug)
CLI_NODE = "fuzz_cli_relay"
BUSY_TOPICS = {"/rosout", "/rosout_agg", "/clock"}
FUZZ = dict(deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))


def serialized(msg) -> bytes:
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


def twists():
    return st.lists(wild_floats(), min_size=6, max_size=6).map(
        lambda v: Twist(linear=Vector3(*v[:3]), angular=Vector3(*v[3:])))


def strings():
    return st.one_of(st.text(max_size=300), st.sampled_from(["", "\x00", "x" * 200000])).map(String)


def arrays():
    return st.lists(wild_floats(), max_size=2000).map(lambda v: Float64MultiArray(data=v))


def topic_names():
    """Names rospy and roscpp take as topics: global, relative or private, in namespaces, and
    the uncleaned forms (doubled or trailing slashes) that roscpp still accepts."""
    return st.tuples(st.sampled_from(["", "/", "~"]), st.lists(valid_names(), min_size=1, max_size=3),
                     st.sampled_from(["/", "//"]), st.sampled_from(["", "/"])).map(
        lambda t: t[0] + t[2].join(t[1]) + t[3])


MARKERS = {String: String("settled"), Twist: Twist(linear=Vector3(x=42.0)),
           Float64MultiArray: Float64MultiArray(data=[42.0])}


class Link:
    """A publisher on IN and a raw recorder on OUT, ready once a probe has come through."""

    def __init__(self, in_topic, out_topic, msg_type, probe, marker=None):
        """`marker` (not equal to `probe`) lets settle() wait out the probes still on their way."""
        self.pub = rospy.Publisher(in_topic, msg_type, queue_size=1000)
        self.out = TopicRecorder(out_topic, rospy.AnyMsg)
        self.marker = marker
        self.ready = wait_for(lambda: self.pub.publish(probe) or self.out.messages, TIMEOUT_S)

    def buffers(self):
        return [m._buff for m in self.out.messages]

    def settle(self) -> bool:
        """Send the marker, wait until it is out (all sent before it is, one connection keeps
        order), then forget what came out."""
        self.pub.publish(self.marker)
        marker = serialized(self.marker)
        arrived = wait_for(lambda: self.buffers()[-1:] == [marker], TIMEOUT_S)
        self.out.clear()
        return bool(arrived)

    def close(self):
        self.pub.unregister()
        self.out.unregister()


class RelayFuzz(unittest.TestCase):
    links = {}

    @classmethod
    def link(cls, name, msg_type, probe, marker):
        if name not in cls.links:
            cls.links[name] = Link("/fuzz/%s_in" % name, "/fuzz/%s_out" % name, msg_type, probe, marker)
        return cls.links[name]

    @settings(max_examples=60, **FUZZ)
    @given(st.one_of(strings().map(lambda m: ("string", String, m)),
                     twists().map(lambda m: ("twist", Twist, m)),
                     arrays().map(lambda m: ("array", Float64MultiArray, m))))
    def test_payloads_come_out_byte_for_byte(self, case):
        name, msg_type, msg = case
        link = self.link(name, msg_type, msg_type(), MARKERS[msg_type])
        self.assertTrue(link.ready, "nothing relayed on /fuzz/%s_in" % name)
        self.assertTrue(link.settle(), "the relay on /fuzz/%s_in stopped relaying" % name)
        link.pub.publish(msg)
        expected = serialized(msg)
        self.assertTrue(wait_for(lambda: link.buffers(), TIMEOUT_S), "a %s was not relayed" % msg_type._type)
        self.assertEqual(link.buffers(), [expected])

    @settings(max_examples=15, **FUZZ)
    @given(st.lists(st.one_of(strings().map(lambda m: ("string", m)),
                              st.tuples(st.just("float"), wild_floats().map(Float64)),
                              st.tuples(st.just("twist"), twists())), min_size=1, max_size=12))
    def test_other_types_are_dropped_with_a_warning(self, sequence):
        switch, feeds = self.switch_ready()
        self.assertTrue(switch.settle(), "the relay stopped relaying after another type came in")
        sentinel = String("end %f" % time.time())
        for kind, msg in sequence:
            (switch.pub if kind == "string" else feeds[kind]).publish(msg)
        switch.pub.publish(sentinel)
        self.assertTrue(wait_for(lambda: serialized(sentinel) in switch.buffers(), TIMEOUT_S),
                        "the relay stopped relaying after another type came in")
        expected = [serialized(m) for kind, m in sequence if kind == "string"] + [serialized(sentinel)]
        self.assertEqual(switch.buffers(), expected, "other types came out of a String relay")

    @classmethod
    def switch_ready(cls):
        """The String relay, warned once about each other type (so both reach it)."""
        if "switch" not in cls.links:
            switch = cls.link("switch", String, String("first"), MARKERS[String])
            assert switch.ready, "nothing relayed on /fuzz/switch_in"
            rosout = RosoutRecorder()
            feeds = {"float": rospy.Publisher("/fuzz/switch_float", Float64, queue_size=1000),
                     "twist": rospy.Publisher("/fuzz/switch_twist", Twist, queue_size=1000)}
            for kind, other in (("float", "std_msgs/Float64"), ("twist", "geometry_msgs/Twist")):
                warned = wait_for(lambda: feeds[kind].publish(Float64() if kind == "float" else Twist()) or [
                    m for m in rosout.matching(r"dropping %s .*forwards std_msgs/String" % other, level=Log.WARN)
                    if m.name.endswith("relay_switch")], TIMEOUT_S)
                assert warned, "no warning from the relay about %s messages on a String topic" % other
            rosout.unregister()
            cls.feeds = feeds
        return cls.links["switch"], cls.feeds

    def test_invalid_names_of_the_issue_exit_with_a_message(self):
        """`relay 'a b' /out` logged FATAL and never exited; topic_tools says the name is not valid."""
        for argv in (["a b", "/out"], ["/in", "a b"], ["/", "/out"], ["1a"]):
            self.check_cli(argv)

    @settings(max_examples=20, phases=(Phase.explicit, Phase.generate), **FUZZ)  # no shrinking: 10 s a hang
    @given(st.one_of(topic_names(), wild_names()), st.one_of(topic_names(), wild_names()))
    def test_random_names_relay_or_exit(self, in_name, out_name):
        assume("\x00" not in in_name + out_name and ":=" not in in_name + out_name)
        self.check_cli([in_name, out_name])

    def check_cli(self, argv):
        names = [argv[0], argv[1] if len(argv) > 1 else argv[0] + "_relay"]
        valid = all(topic_name_problem(n) is None for n in names)
        resolved = [rosgraph.names.resolve_name(n, "/" + CLI_NODE) if valid else n for n in names]
        assume(not valid or (resolved[0] != resolved[1] and not BUSY_TOPICS & set(resolved)
                             and not any(r.startswith("/fuzz/") for r in resolved)))
        log_path = os.path.join(tempfile.mkdtemp(), "relay.log")
        relay = NodeProcess.rosrun("course_relay", "relay", argv + ["__name:=" + CLI_NODE], log_path=log_path)
        try:
            if valid:
                link = Link(resolved[0], resolved[1], String, String("relayed"))
                link.close()
                self.assertTrue(link.ready, "relay %r: nothing relayed from %s to %s\n%s"
                                % (argv, resolved[0], resolved[1], relay.output()))
            else:
                self.assertTrue(wait_for(lambda: not relay.running(), EXIT_S),
                                "relay %r still runs %d s after an invalid name\n%s" % (argv, EXIT_S, relay.output()))
                self.assertNotEqual(relay.proc.returncode, 0)
                self.assertIn("is not a valid topic name", relay.output())
        finally:
            relay.stop()


if __name__ == "__main__":
    rospy.init_node("relay_fuzz")
    rostest.rosrun("course_relay", "relay_fuzz", RelayFuzz)
