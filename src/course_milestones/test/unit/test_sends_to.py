"""discovery.sends_to reads a node's own bus info (the slave API's getBusInfo) without a master:
fake nodes answer with rospy's and roscpp's form, with odd forms, or not at all. Whatever a
node answers, sends_to says True, False or None and never raises."""
import socket

from hypothesis import given, settings, strategies as st

from course_milestones import discovery
from course_testkit import xmlrpc_fake

CHECK = "/turtlebot_check"
TOPIC = "/cmd_vel"


def node_answering(reply):
    """A fake node whose getBusInfo returns `reply`; a context giving its URI."""
    return xmlrpc_fake.serving({"getBusInfo": lambda caller_id: reply})


def bus(*connections):
    return [1, "bus info", [list(c) for c in connections]]


def test_a_publication_to_us_is_seen():
    # rospy: (id, subscriber's caller id, "o", transport, topic, connected, info); roscpp the same
    with node_answering(bus((3, CHECK, "o", "TCPROS", TOPIC, True, "TCPROS connection on port 1 to [x]"))) as uri:
        assert discovery.sends_to(uri, TOPIC, CHECK) is True


def test_a_publication_to_someone_else_or_on_another_topic_is_not_ours():
    connections = bus((1, "/rosout", "o", "TCPROS", "/rosout", True, ""),
                      (2, "/other_listener", "o", "TCPROS", TOPIC, True, ""),
                      (3, CHECK, "o", "TCPROS", "/turtle1/cmd_vel", True, ""))
    with node_answering(connections) as uri:
        assert discovery.sends_to(uri, TOPIC, CHECK) is False


def test_an_inbound_connection_from_us_is_not_a_publication():
    # a node subscribing to our topic lists us as "i" (and by URI in rospy): not what is waited for
    with node_answering(bus((1, CHECK, "i", "TCPROS", TOPIC, True, ""))) as uri:
        assert discovery.sends_to(uri, TOPIC, CHECK) is False


def test_no_connections_yet():
    with node_answering(bus()) as uri:
        assert discovery.sends_to(uri, TOPIC, CHECK) is False


def test_an_error_code_or_another_form_cannot_tell():
    for reply in ([0, "no", []], [-1, "error", []], [1, "bus info", "none"], "text", [1], None, {"a": 1}):
        with node_answering(reply) as uri:
            assert discovery.sends_to(uri, TOPIC, CHECK) is None, reply


def test_nobody_listening_cannot_tell():
    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))
    port = sock.getsockname()[1]
    sock.close()
    assert discovery.sends_to("http://127.0.0.1:%d/" % port, TOPIC, CHECK) is None
    assert discovery.sends_to("not a uri", TOPIC, CHECK) is None


def test_a_node_that_never_answers_cannot_tell_within_the_timeout(monkeypatch):
    monkeypatch.setattr(discovery, "NODE_CALL_TIMEOUT_S", 0.3)
    listener = socket.socket()
    listener.bind(("127.0.0.1", 0))
    listener.listen(1)  # accepts (the kernel's backlog) and never answers
    try:
        assert discovery.sends_to("http://127.0.0.1:%d/" % listener.getsockname()[1], TOPIC, CHECK) is None
    finally:
        listener.close()


xmlrpc_values = st.recursive(
    st.none() | st.booleans() | st.integers(-2**31, 2**31 - 1) | st.text(max_size=20)
    | st.sampled_from([CHECK, TOPIC, "o", "i", "TCPROS"]),
    lambda inner: st.lists(inner, max_size=8), max_leaves=30)


@settings(max_examples=60, deadline=None)
@given(st.one_of(xmlrpc_values, st.tuples(st.sampled_from([1, 0, -1]), st.text(max_size=5), xmlrpc_values)
                 .map(list)))
def test_any_answer_gives_true_false_or_none(reply):
    with node_answering(reply) as uri:
        assert discovery.sends_to(uri, TOPIC, CHECK) in (True, False, None)
