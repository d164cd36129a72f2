#!/usr/bin/env python3
"""course_milestones.guard against real fakes (test/nodes/fake_simulator.py) beside a real turtlesim:
a fake publisher of a simulator topic never reaches the check, a fake service is never called,
save_canvas copies nothing from a fake snapshot service, a topic that becomes the simulator's
later loses its fake connection, a stolen simulator name is seen, and @judged turns each of
these into a failure that names the student's node first. Each case first shows that the fake
works (without the guard, or under a name the simulator does not use), so that a guard doing
nothing would fail it. The tests run in name order; the last one takes turtlesim's name, which
shuts turtlesim down."""
import os
import sys
import unittest

import rosgraph
import rospy
import rostest
from std_srvs.srv import Trigger
from turtlesim.msg import Pose
from turtlesim.srv import Spawn, TeleportAbsolute

from course_milestones import guard
from course_milestones.trusted import TURTLESIM
from course_checks.artifacts import PNG_SIGNATURE, artifact_path, save_canvas
from course_checks.nodes import NodeProcess
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

FAKE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fake_simulator.py")
FAKE_X = 42.0
TIMEOUT_S = 15.0
REAL_POSES = 60  # ~1 s of turtlesim's poses at 62.5 Hz


def fakes(recorder: TopicRecorder) -> list:
    return [m for m in recorder.messages if m.x == FAKE_X]


def endpoints(recorder: TopicRecorder) -> set:
    return {c.endpoint_id for c in recorder.sub.impl.connections}


def lookup_node(name: str):
    try:
        return rosgraph.Master("/trust_guard_check").lookupNode(name)
    except rosgraph.MasterException:
        return None


def lookup_service(name: str):
    try:
        return rosgraph.Master("/trust_guard_check").lookupService(name)
    except rosgraph.MasterException:
        return None


class TrustGuard(unittest.TestCase):
    longMessage = False

    def setUp(self):
        self.guard = guard.active()
        self.processes = []
        self.recorders = []

    def tearDown(self):
        for recorder in self.recorders:
            recorder.unregister()
        for process in self.processes:
            process.stop()

    def fake(self, *args: str) -> NodeProcess:
        """Start fake_simulator.py with `args`; returns it once it has registered everything."""
        process = NodeProcess([sys.executable, FAKE] + list(args), log_path=artifact_path("fake"))
        self.processes.append(process)
        self.assertTrue(wait_for(lambda: "READY" in process.output() or not process.running(), TIMEOUT_S)
                        and process.running(), "the fake did not start: %s" % process.output())
        return process

    def record(self, topic: str) -> TopicRecorder:
        recorder = TopicRecorder(topic, Pose)
        self.recorders.append(recorder)
        return recorder

    def violation(self, start: str) -> str:
        """The guard's violation starting with `start`, once it has one."""
        return wait_for(lambda: next((v for v in self.guard.policy.violations if v.startswith(start)), ""), TIMEOUT_S)

    def test_1_record(self):
        policy = self.guard.policy
        self.assertIsNone(policy.problem)
        self.assertEqual(policy.own_uri, rospy.get_node_uri())
        self.assertTrue(policy.own_uri)
        self.assertEqual(policy.trusted_uris, {"/turtlesim": lookup_node("/turtlesim")})
        self.assertIn(lookup_service("/spawn"), policy.trusted_endpoints)
        self.assertTrue(set(TURTLESIM.topics) <= set(policy.guarded_topics))
        self.assertTrue(set(TURTLESIM.services) <= set(policy.guarded_services))
        self.assertNotIn("/rosout", policy.guarded_topics)

    def test_2_a_fake_pose_never_reaches_the_check(self):
        poses = self.record("/turtle1/pose")
        self.assertTrue(wait_for(lambda: poses.count, TIMEOUT_S), "no pose from turtlesim")
        self.fake("--name", "fake_pose", "--pose", "/turtle1/pose")
        said = self.violation("your node /fake_pose publishes /turtle1/pose, which only turtlesim may publish")
        self.assertTrue(said, "no violation: %s" % self.guard.policy.violations)
        mark = poses.count
        self.assertTrue(wait_for(lambda: poses.count >= mark + REAL_POSES, TIMEOUT_S))
        self.assertEqual(fakes(poses), [])
        self.assertEqual(endpoints(poses), {lookup_node("/turtlesim")})
        # The fake does publish: without the guard, a new subscription hears it (rospy shares one
        # subscription per topic in a process, so the guarded one goes first).
        poses.unregister()
        self.recorders.remove(poses)
        guard.uninstall()
        try:
            unguarded = self.record("/turtle1/pose")
            self.assertTrue(wait_for(lambda: fakes(unguarded), TIMEOUT_S), "the fake publishes nothing")
        finally:
            guard.activate(self.guard)

    def test_3_a_topic_that_becomes_the_simulators_drops_its_fake(self):
        poses = self.record("/turtle2/pose")
        fake = self.fake("--name", "early_bird", "--pose", "/turtle2/pose")
        self.assertTrue(wait_for(lambda: fakes(poses), TIMEOUT_S), "before the spawn, /turtle2/pose is nobody's")
        rospy.ServiceProxy("/spawn", Spawn)(2.0, 2.0, 0.0, "turtle2")
        said = self.violation("your node /early_bird publishes /turtle2/pose")
        self.assertTrue(said, "no violation: %s" % self.guard.policy.violations)
        fake_uri = lookup_node("/early_bird")
        self.assertTrue(wait_for(lambda: fake_uri not in endpoints(poses), TIMEOUT_S),
                        "the fake's connection stays open")
        self.assertTrue(fake.running())
        mark = poses.count
        self.assertTrue(wait_for(lambda: poses.count >= mark + REAL_POSES, TIMEOUT_S), "no pose from turtle2")
        # at most one message read before the close may still be handed over right after it
        self.assertEqual([m for m in poses.messages[mark + 1:] if m.x == FAKE_X], [])

    def test_4_a_fake_service_is_never_called(self):
        real = lookup_service("/turtle1/teleport_absolute")
        fake = self.fake("--name", "fake_teleport", "--teleport", "/turtle1/teleport_absolute",
                         "--teleport", "/fake_teleport/free")
        self.assertTrue(wait_for(lambda: lookup_service("/turtle1/teleport_absolute") != real, TIMEOUT_S))
        with self.assertRaises(rospy.ServiceException) as raised:
            rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)(1.0, 1.0, 0.0)
        self.assertTrue(str(raised.exception).startswith(
            "your node /fake_teleport offers the service /turtle1/teleport_absolute, which only turtlesim may offer"),
            str(raised.exception))
        # The same fake under a name turtlesim does not use is called, and says so.
        rospy.ServiceProxy("/fake_teleport/free", TeleportAbsolute)(1.0, 1.0, 0.0)
        self.assertTrue(wait_for(lambda: "CALLED /fake_teleport/free" in fake.output(), TIMEOUT_S))
        self.assertNotIn("CALLED /turtle1/teleport_absolute", fake.output())

    def test_5_save_canvas_copies_nothing_from_a_fake_snapshot(self):
        picture = artifact_path("planted", ".png")
        with open(picture, "wb") as out:
            out.write(PNG_SIGNATURE + b"planted by the student")
        real = lookup_service("/turtlesim/snapshot")
        self.fake("--name", "fake_snapshot", "--snapshot", "/turtlesim/snapshot", "--snapshot",
                  "/fake_snapshot/free", "--path", picture)
        self.assertTrue(wait_for(lambda: lookup_service("/turtlesim/snapshot") != real, TIMEOUT_S))
        self.assertIsNone(save_canvas("/turtlesim/snapshot", "stolen"))
        self.assertTrue(self.violation("your node /fake_snapshot offers the service /turtlesim/snapshot"))
        copied = save_canvas("/fake_snapshot/free", "free")  # the fake works: unguarded, its PNG is copied
        self.assertIsNotNone(copied)
        with open(copied, "rb") as f:
            self.assertEqual(f.read(), PNG_SIGNATURE + b"planted by the student")
        self.fake("--name", "fake_passwd", "--snapshot", "/fake_passwd/free", "--path", "/etc/passwd")
        self.assertIsNone(save_canvas("/fake_passwd/free", "passwd"), "a file that is not a PNG is never copied")

    def test_6_judged_fails_a_passing_test_with_the_violation_first(self):
        @guard.judged
        class Passing(unittest.TestCase):
            def test_passes(self):
                pass

            def test_fails_otherwise(self):
                self.fail("the pen did not turn red")
        result = unittest.TestResult()
        unittest.defaultTestLoader.loadTestsFromTestCase(Passing).run(result)
        messages = {test.id().rsplit(".", 1)[-1]: text.strip().splitlines()[-1] for test, text in result.failures}
        self.assertEqual(sorted(messages), ["test_fails_otherwise", "test_passes"], result.errors)
        for message in messages.values():
            self.assertTrue(message.startswith("AssertionError: your node /fake_pose publishes /turtle1/pose"), message)
        self.assertIn("(besides, the check saw: the pen did not turn red)", messages["test_fails_otherwise"])

    def test_7_a_stolen_simulator_name_is_seen(self):
        recorded = self.guard.policy.trusted_uris["/turtlesim"]
        self.fake("--name", "turtlesim", "--pose", "/turtle1/pose")
        self.assertTrue(wait_for(lambda: lookup_node("/turtlesim") not in (None, recorded), TIMEOUT_S))
        verdict = self.guard.audit()
        self.assertTrue(any(v.startswith("a node of yours took the name /turtlesim, which is turtlesim's")
                            for v in verdict), verdict)
        poses = self.record("/turtle1/pose")
        # rospy decides on the connection before it makes it: once refused, nothing comes from there
        self.assertTrue(self.violation("your node /turtlesim publishes /turtle1/pose"))
        self.assertNotIn(lookup_node("/turtlesim"), endpoints(poses))
        self.assertEqual(fakes(poses), [])


if __name__ == "__main__":
    rospy.init_node("trust_guard_check")
    guard.install([TURTLESIM])
    rostest.rosrun("course_milestones", "trust_guard", TrustGuard)
