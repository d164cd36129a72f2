"""course_web.lab_status and master_cache without ROS: a fake master that counts what it is asked,
a clock the test steps. Many clients and questions cost one round; a round asks the topic types
only when the state changed and the canvas's publishers at most every few seconds; a client is
told each part once and then only on a change; the master stopping, a node dying silently and a
node coming are told; the thread outlives a failing master."""
from __future__ import annotations

import collections
import json

import pytest

from course_checks.waiting import wait_for
from course_web import introspect
from course_web.lab_status import LabStatus, Wants
from course_web.master_cache import LIVENESS_PERIOD_S, TYPES_PERIOD_S, normalised

SCENE = "/turtlesim/scene"
DOWN = "the ROS master at http://localhost:11311 does not answer: [Errno 111] Connection refused"


class CountingMaster:
    """A master whose graph the test changes, counting every question."""

    def __init__(self) -> None:
        self.publishers = {SCENE: ["/turtlesim"], "/turtle1/pose": ["/turtlesim"]}
        self.subscribers = {"/turtle1/cmd_vel": ["/turtlesim"]}
        self.types = {SCENE: "std_msgs/String", "/turtle1/pose": "turtlesim/Pose",
                      "/turtle1/cmd_vel": "geometry_msgs/Twist"}
        self.dead = set()
        self.down = False
        self.broken = False
        self.asked = collections.Counter()

    def _check(self, question):
        self.asked[question] += 1
        if self.broken:
            raise KeyError("a bug")
        if self.down:
            raise introspect.ApiError(DOWN, 503)

    def system_state(self):
        self._check("getSystemState")
        # in the master's own order, which need not be stable
        return [[[t, list(reversed(n))] for t, n in reversed(list(self.publishers.items()))],
                [[t, list(n)] for t, n in self.subscribers.items()], []]

    def topic_types(self):
        self._check("getTopicTypes")
        return dict(self.types)

    def node_answers(self, name):
        self.asked["getPid " + name] += 1
        return name not in self.dead


class Clock:
    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


class Inbox:
    """What one client was told, by part."""

    def __init__(self) -> None:
        self.frames = []

    def __call__(self, part, text):
        message = json.loads(text)
        assert message["op"] == "lab_status" and list(message) == ["op", part]
        self.frames.append((part, message[part]))

    def last(self, part):
        return [answer for p, answer in self.frames if p == part][-1]

    def parts(self):
        return [p for p, _ in self.frames]


@pytest.fixture
def lab():
    master, clock = CountingMaster(), Clock()
    status = LabStatus(master, clock=clock, threaded=False)  # the test runs the rounds itself
    yield master, clock, status
    status.stop()


def rounds(status, clock, seconds, step=0.25):
    """Run the rounds that fall due in `seconds` of the test's clock, as the thread would."""
    end = clock.now + seconds
    while clock.now < end:
        if status.due_in() == 0:
            status.step()
        clock.now += step


def test_every_client_is_told_each_part_once_and_the_steady_state_asks_one_call_a_period(lab):
    master, clock, status = lab
    inboxes = [Inbox() for _ in range(10)]
    for number, inbox in enumerate(inboxes):
        status.watch(number, Wants(health="/turtlesim/scene", graph=True, topics=True), inbox)
    status.step()
    for inbox in inboxes:
        assert sorted(inbox.parts()) == ["graph", "health", "topics"]
        assert inbox.last("health")["state"] == "ok" and inbox.last("health")["publishers"] == ["/turtlesim"]
        assert inbox.last("graph")["nodes"] == ["/turtlesim"]
        assert {"name": SCENE, "type": "std_msgs/String"} in inbox.last("topics")["topics"]
    assert master.asked == {"getSystemState": 1, "getTopicTypes": 1, "getPid /turtlesim": 1}
    master.asked.clear()
    rounds(status, clock, 15.0)  # nothing changes for 15 s
    assert all(len(inbox.frames) == 3 for inbox in inboxes), "a client was told what it knew already"
    assert master.asked["getSystemState"] == pytest.approx(15.0 / status.state_period_s, abs=1)
    assert master.asked["getTopicTypes"] == 0
    assert master.asked["getPid /turtlesim"] == pytest.approx(15.0 / LIVENESS_PERIOD_S, abs=1)
    # the types are asked again now and then, even when nothing changed
    master.asked.clear()
    rounds(status, clock, TYPES_PERIOD_S)
    assert master.asked["getTopicTypes"] == 1


def test_nobody_watching_asks_nothing_and_a_new_client_is_told_at_once_from_a_recent_round(lab):
    master, clock, status = lab
    assert status.due_in() is None
    rounds(status, clock, 10.0)
    assert not master.asked
    first = Inbox()
    status.watch("first", Wants(health=""), first)  # "": the canvas's default topic
    assert status.due_in() == 0 and not first.frames  # the cache is old: told after the round
    status.step()
    assert first.last("health")["topic"] == SCENE
    second = Inbox()
    status.watch("second", Wants(graph=True, debug=True), second)  # the cache is recent: told at once
    assert second.parts() == ["graph"] and master.asked["getSystemState"] == 1
    status.unwatch("first")
    status.unwatch("second")
    assert status.due_in() is None


def test_changes_are_told_to_those_who_want_them(lab):
    master, clock, status = lab
    everything, graph_only = Inbox(), Inbox()
    status.watch("everything", Wants(health=SCENE, graph=True, topics=True), everything)
    status.watch("graph", Wants(graph=True), graph_only)
    status.step()
    # a node comes: the graph and the topics change, the health does not
    master.publishers["/pose_copy"] = ["/pose_relay"]
    master.subscribers["/turtle1/pose"] = ["/pose_relay"]
    master.types["/pose_copy"] = "turtlesim/Pose"
    rounds(status, clock, 2.0)
    assert everything.parts() == ["health", "graph", "topics", "graph", "topics"]
    assert "/pose_relay" in everything.last("graph")["nodes"]
    assert graph_only.parts() == ["graph", "graph"]
    # turtlesim killed by SIGKILL: still registered, silent; told within the liveness period
    master.dead.add("/turtlesim")
    rounds(status, clock, LIVENESS_PERIOD_S + status.state_period_s)
    health = everything.last("health")
    assert health["state"] == "no-publisher" and "still registered, but does not answer" in health["says"]
    # the master stops: every part says so, at the next round
    master.down = True
    rounds(status, clock, status.state_period_s + 0.5)
    assert everything.last("health")["state"] == "no-master"
    assert everything.last("health")["says"].startswith("The ROS master at http://localhost:11311 does not answer")
    assert everything.last("graph") == {"error": DOWN} and everything.last("topics") == {"error": DOWN}
    told = len(everything.frames)
    rounds(status, clock, 5.0)
    assert len(everything.frames) == told, "the same news was told twice"
    # it starts again, turtlesim too: ok again
    master.down = False
    master.dead.clear()
    rounds(status, clock, status.state_period_s + 0.5)
    assert everything.last("health")["state"] == "ok" and "error" not in everything.last("graph")


def test_a_client_that_changes_what_it_wants_is_told_the_new_parts(lab):
    master, clock, status = lab
    inbox = Inbox()
    status.watch("page", Wants(health=SCENE), inbox)
    status.step()
    status.watch("page", Wants(health=SCENE, graph=True), inbox)  # the graph panel scrolled into view
    assert inbox.parts() == ["health", "health", "graph"]
    status.watch("page", Wants(health="/other/scene"), inbox)  # another turtlesim node typed in
    assert inbox.last("health")["state"] == "no-publisher" and inbox.last("health")["topic"] == "/other/scene"


def test_the_api_shares_the_cache(lab):
    master, clock, status = lab
    for _ in range(20):
        assert status.answer(lambda m: introspect.graph(m))["nodes"] == ["/turtlesim"]
        assert status.answer(lambda m: introspect.health(m, SCENE))["state"] == "ok"
    assert master.asked == {"getSystemState": 1, "getTopicTypes": 1, "getPid /turtlesim": 1}
    clock.now += 1.0
    status.answer(introspect.topics)
    assert master.asked["getSystemState"] == 2
    master.down = True
    clock.now += 1.0
    with pytest.raises(introspect.ApiError, match="does not answer") as raised:
        status.answer(introspect.topics)
    assert raised.value.status == 503


def test_the_watching_thread_outlives_a_failing_master():
    master = CountingMaster()
    master.broken = True
    warnings = []
    status = LabStatus(master, state_period_s=0.05, warn=warnings.append)
    try:
        inbox = Inbox()
        status.watch("page", Wants(health=SCENE), inbox)
        assert wait_for(lambda: master.asked["getSystemState"] >= 3, 10.0), "the thread stopped asking"
        assert warnings and "a bug" in warnings[0] and len(warnings) < master.asked["getSystemState"]
        master.broken = False
        assert wait_for(lambda: inbox.frames, 10.0), "the thread did not recover"
        assert inbox.last("health")["state"] == "ok"
        status.unwatch("page")
        assert status.due_in() is None  # what the thread waits on: nobody watching, nothing due
    finally:
        status.stop()
    assert not status.thread.is_alive()


def test_the_state_compares_whatever_the_masters_order():
    a = [[["/a", ["/n1", "/n2"]], ["/b", ["/n3"]]], [], []]
    b = [[["/b", ["/n3"]], ["/a", ["/n2", "/n1"]]], [], []]
    assert normalised(a) == normalised(b)
    with pytest.raises(ValueError):
        normalised([[], []])
