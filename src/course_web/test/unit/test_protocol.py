"""course_web.protocol: one client's rosbridge v2 session against a fake Bridge."""
from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from course_web.outbox import Outbox
from course_web import protocol
from course_web.protocol import Bridge, RequestError, Session, publish_frame


class FakeBridge(Bridge):
    """Records what the session asked; knows one topic type and one service."""

    TOPICS = {"/turtle1/cmd_vel": "geometry_msgs/Twist", "/chatter": "std_msgs/String"}

    def __init__(self) -> None:
        self.calls = []
        self.readers = {}

    def advertise(self, client, topic, type_name, latch, queue_size):
        known = self.TOPICS.get(topic)
        if type_name and known and known != type_name:
            raise RequestError("type mismatch: %s has type %s, not %s" % (topic, known, type_name))
        if not (type_name or known):
            raise RequestError("unknown topic %s" % topic)
        self.calls.append(("advertise", topic, type_name or known))

    def unadvertise(self, client, topic):
        self.calls.append(("unadvertise", topic))

    def publish(self, client, topic, msg):
        if not isinstance(msg, dict):
            raise RequestError("%s: expected an object" % topic)
        self.calls.append(("publish", topic, msg))

    def subscribe(self, client, key, topic, type_name, compression, deliver):
        if topic not in self.TOPICS:
            raise RequestError("unknown topic %s" % topic)
        self.readers[key] = deliver
        self.calls.append(("subscribe", topic, compression))
        return self.TOPICS[topic]

    def unsubscribe(self, client, key):
        self.readers.pop(key)
        self.calls.append(("unsubscribe", key))

    def call_service(self, service, type_name, args, done):
        if service == "/spawn":
            done(True, {"name": "turtle2"})
        else:
            done(False, "unknown service %s" % service)


@pytest.fixture
def session():
    return Session("c1", FakeBridge(), Outbox(), max_message_bytes=1000)


def replies(session, now=0.0):
    out = []
    while True:
        payload = session.outbox.take(now)
        if payload is None:
            return out
        out.append(json.loads(payload))


def only_error(session, request_id=None):
    [reply] = replies(session)
    assert reply["op"] == "status" and reply["level"] == "error"
    if request_id is not None:
        assert reply["id"] == request_id
    return reply["msg"]


@pytest.mark.parametrize("frame, complaint", [
    ("{not json", "malformed JSON"),
    ("[1, 2]", "must be a JSON object"),
    ('{"op": "explode"}', "unknown op 'explode'"),
    ('{"no_op": 1}', "unknown op None"),
    ('{"op": "subscribe"}', "subscribe needs a \"topic\" field"),
    ('{"op": "subscribe", "topic": 5}', "\"topic\" must be a string"),
    ('{"op": "subscribe", "topic": "/nowhere", "type": "std_msgs/String"}', "unknown topic /nowhere"),
    ('{"op": "subscribe", "topic": "/chatter", "throttle_rate": "often"}', "\"throttle_rate\" must be a number"),
    ('{"op": "subscribe", "topic": "/chatter", "compression": "zip"}', "compression 'zip' is not supported"),
    ('{"op": "advertise", "topic": "/turtle1/cmd_vel"}', "advertise needs a \"type\" field"),
    ('{"op": "advertise", "topic": "/turtle1/cmd_vel", "type": "std_msgs/String"}', "type mismatch"),
    ('{"op": "unadvertise", "topic": "/chatter"}', "/chatter is not advertised by this client"),
    ('{"op": "unsubscribe", "topic": "/chatter"}', "no subscription to /chatter"),
    ('{"op": "publish", "topic": "/nowhere", "msg": {}}', "unknown topic /nowhere"),
    ('{"op": "call_service", "service": "/spawn", "args": 3}', "\"args\" must be an object or a list"),
    ("x" * 1001, "message of 1001 bytes refused: the limit is 1000 bytes"),
])
def test_each_bad_request_gets_one_clear_error(session, frame, complaint):
    session.handle(frame)
    assert complaint in only_error(session)


def test_the_error_carries_the_request_id(session):
    session.handle('{"op": "subscribe", "id": "sub:7", "topic": "/nowhere"}')
    assert "unknown topic" in only_error(session, "sub:7")


def test_subscribe_delivers_into_its_own_lane_and_unsubscribe_stops_it(session):
    session.handle('{"op": "subscribe", "id": "s1", "topic": "chatter", "queue_length": 2}')
    assert replies(session) == []
    [deliver] = session.bridge.readers.values()
    for n in range(3):
        deliver(publish_frame("/chatter", {"data": str(n)}))
    assert [r["msg"]["data"] for r in replies(session)] == ["1", "2"]  # queue_length 2: oldest dropped
    session.handle('{"op": "unsubscribe", "id": "s1", "topic": "/chatter"}')
    assert session.bridge.readers == {} and replies(session) == []


def test_publish_advertises_on_first_use_with_the_masters_type(session):
    session.handle('{"op": "publish", "topic": "/turtle1/cmd_vel", "msg": {"linear": {"x": 1}}}')
    assert session.bridge.calls == [("advertise", "/turtle1/cmd_vel", "geometry_msgs/Twist"),
                                    ("publish", "/turtle1/cmd_vel", {"linear": {"x": 1}})]


def test_call_service_answers_with_values_and_result(session):
    session.handle('{"op": "call_service", "id": "c1", "service": "/spawn", "args": {"x": 1}}')
    assert replies(session) == [{"op": "service_response", "id": "c1", "service": "/spawn",
                                 "result": True, "values": {"name": "turtle2"}}]
    session.handle('{"op": "call_service", "id": "c2", "service": "/nope"}')
    status, response = replies(session)
    assert status["op"] == "status" and "unknown service /nope" in status["msg"]
    assert response == {"op": "service_response", "id": "c2", "service": "/nope", "result": False,
                        "values": "unknown service /nope"}


def test_close_drops_the_clients_subscriptions_and_publishers(session):
    session.handle('{"op": "subscribe", "topic": "/chatter"}')
    session.handle('{"op": "advertise", "topic": "/turtle1/cmd_vel", "type": "geometry_msgs/Twist"}')
    session.close()
    assert session.bridge.readers == {}
    assert ("unadvertise", "/turtle1/cmd_vel") in session.bridge.calls
    session.handle('{"op": "subscribe", "topic": "/chatter"}')  # a request that was still on its way
    assert session.bridge.readers == {} and replies(session) == []


@settings(max_examples=300, deadline=None)
@given(st.one_of(st.text(max_size=200), st.binary(max_size=200),
                 st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=10),
                              lambda inner: st.lists(inner, max_size=4) | st.dictionaries(
                                  st.sampled_from(["op", "id", "topic", "type", "msg", "args", "service",
                                                   "throttle_rate", "queue_length", "compression"]), inner, max_size=6),
                              max_leaves=20).map(json.dumps)))
def test_no_frame_escapes_as_an_exception(frame):
    """Whatever a client sends, the session answers (or stays quiet) and never raises."""
    session = Session("c", FakeBridge(), Outbox(), max_message_bytes=1000)
    session.handle(frame)
    for reply in replies(session):
        assert reply["op"] in ("status", "service_response")


def test_a_failure_inside_the_bridge_becomes_an_error_not_a_dead_session(session):
    def broken(*args):
        raise ConnectionResetError("master went away")
    session.bridge.subscribe = broken
    session.handle('{"op": "subscribe", "id": "s", "topic": "/chatter"}')
    assert "master went away" in only_error(session, "s")
    session.handle('{"op": "advertise", "topic": "/chatter", "type": "std_msgs/String"}')
    assert replies(session) == []


class SlowBridge(FakeBridge):
    """Keeps every call's done() for the test to answer later (a service that does not answer yet)."""

    def __init__(self) -> None:
        super().__init__()
        self.pending = []

    def call_service(self, service, type_name, args, done):
        self.pending.append(done)


def test_a_client_waits_for_its_own_slow_calls_only():
    slow = SlowBridge()
    mine = Session("mine", slow, Outbox())
    other = Session("other", slow, Outbox())
    for n in range(protocol.MAX_CALLS_IN_FLIGHT):
        mine.handle(json.dumps({"op": "call_service", "id": "c%d" % n, "service": "/slow"}))
    assert len(slow.pending) == protocol.MAX_CALLS_IN_FLIGHT and not replies(mine)
    mine.handle(json.dumps({"op": "call_service", "id": "one-too-many", "service": "/slow"}))
    assert "still waiting" in only_error(mine, "one-too-many")
    other.handle(json.dumps({"op": "call_service", "id": "theirs", "service": "/slow"}))
    assert len(slow.pending) == protocol.MAX_CALLS_IN_FLIGHT + 1  # another client is not held up
    slow.pending[0](True, {})
    slow.pending[0](True, {})  # a second answer to the same call is ignored
    assert [(m["op"], m["id"]) for m in replies(mine)] == [("service_response", "c0")]
    mine.handle(json.dumps({"op": "call_service", "id": "again", "service": "/slow"}))
    assert len(slow.pending) == protocol.MAX_CALLS_IN_FLIGHT + 2 and not replies(mine)


class FakeStatus:
    """course_web.lab_status's side of the lab_status op: records what each client wants."""

    def __init__(self) -> None:
        self.watching = {}

    def watch(self, client, wants, deliver):
        self.watching[client] = (wants, deliver)
        for part, _ in wants.parts():
            deliver(part, json.dumps({"op": "lab_status", part: {"told": part}}))

    def unwatch(self, client):
        self.watching.pop(client, None)


def test_lab_status_is_told_in_a_queue_of_one_per_part_and_ends_with_a_request_for_nothing():
    status = FakeStatus()
    session = Session("c1", FakeBridge(), Outbox(), status=status)
    session.handle(json.dumps({"op": "lab_status", "health": "/turtlesim/scene", "graph": True, "debug": True}))
    wants, deliver = status.watching["c1"]
    assert (wants.health, wants.graph, wants.debug, wants.topics) == ("/turtlesim/scene", True, True, False)
    for number in range(5):  # the graph changes five times before the client reads: it gets the newest
        deliver("graph", json.dumps({"op": "lab_status", "graph": {"n": number}}))
    told = replies(session)
    assert {"op": "lab_status", "health": {"told": "health"}} in told
    assert [m["graph"] for m in told if "graph" in m] == [{"n": 4}]
    session.handle(json.dumps({"op": "lab_status", "health": "/turtlesim/scene"}))  # the graph scrolled away
    deliver = status.watching["c1"][1]
    deliver("graph", "a late graph")
    assert [m for m in replies(session) if "graph" in m] == []
    session.handle(json.dumps({"op": "lab_status"}))
    assert "c1" not in status.watching and not replies(session)
    session.handle(json.dumps({"op": "lab_status", "topics": True}))
    session.close()
    assert "c1" not in status.watching


@pytest.mark.parametrize("request_, complaint", [
    ({"graph": "yes"}, '"graph" must be true or false'),
    ({"health": 5}, '"health" must be a string'),
    ({"health": "/t" * 600}, "at most 1000"),
    ({"topics": 1}, '"topics" must be true or false'),
])
def test_bad_lab_status_requests_say_why(request_, complaint):
    status = FakeStatus()
    session = Session("c1", FakeBridge(), Outbox(), status=status)
    session.handle(json.dumps(dict(request_, op="lab_status", id="ls")))
    assert complaint in only_error(session, "ls") and not status.watching


def test_lab_status_without_a_master_says_so(session):
    session.handle(json.dumps({"op": "lab_status", "health": ""}))
    assert "no ROS master to watch" in only_error(session)
