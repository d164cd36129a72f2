"""inbound_headers.WaitingHeaders over real sockets, no master: a complete header goes on with its
bytes replayed and nothing after it read; a connection closed mid-header, one without a header in
time, one announcing too long a header and the oldest past the bound are closed, with one
(throttled) warning; waiting costs no wake-ups of its thread."""
import io
import socket
import struct
import threading
from typing import List

import pytest
from rosgraph.network import read_ros_handshake_header, write_ros_handshake_header

from course_checks.waiting import wait_for
from course_rospy.inbound_headers import ReplaySocket, WaitingHeaders

FIELD = b"callerid=/x"
HEADER = struct.pack("<I", len(FIELD) + 4) + struct.pack("<I", len(FIELD)) + FIELD
DEADLINE_S = 1.0


class Node:
    """A WaitingHeaders with its handed-on sockets and warnings recorded."""

    def __init__(self, **limits) -> None:
        self.handed: List[socket.socket] = []
        self.warnings: List[str] = []
        self.handed_on = threading.Event()
        self.headers = WaitingHeaders(self._hand_on, self.warnings.append, **limits)

    def _hand_on(self, sock, address) -> None:
        self.handed.append(sock)
        self.handed_on.set()

    def connection(self, sent: bytes = b"") -> socket.socket:
        """The client's end of a new connection the node waits on, which has `sent` so far."""
        ours, theirs = socket.socketpair()
        theirs.sendall(sent)
        self.headers.add(ours, ("peer", 1))
        return theirs


@pytest.fixture
def node():
    n = Node()
    yield n
    n.headers.close()
    for sock in n.handed:
        sock.close()


def closed(sock: socket.socket) -> bool:
    """Whether the far end of `sock` has closed (a read sees the end), without waiting."""
    sock.setblocking(False)
    try:
        return sock.recv(1) == b""
    except BlockingIOError:
        return False
    except ConnectionResetError:
        return True


def test_a_complete_header_is_handed_on_replayed_and_nothing_after_it_is_read(node):
    client = node.connection()
    client.sendall(HEADER[:3])
    assert wait_for(lambda: node.headers.waiting() == 1, DEADLINE_S)
    client.sendall(HEADER[3:] + b"request")
    assert node.handed_on.wait(DEADLINE_S)
    sock = node.handed[0]
    assert isinstance(sock, ReplaySocket) and sock.gettimeout() is None
    assert sock.recv(4, socket.MSG_PEEK) == HEADER[:4]
    assert sock.recv(4096) == HEADER  # rospy's header read: the header, not a byte more
    assert sock.recv(4096) == b"request"
    sock.sendall(b"answer")
    assert client.recv(100) == b"answer"
    assert node.headers.waiting() == 0 and node.warnings == []


def test_rospys_header_read_gets_the_header_and_leaves_what_follows(node):
    """What rospy's handler does first with the socket it is handed (rosgraph's own function)."""
    client = node.connection()
    header = {"callerid": "/caller", "topic": "/t", "message_definition": "string data\n" * 1000}
    write_ros_handshake_header(client, header)
    client.sendall(b"next")
    assert node.handed_on.wait(DEADLINE_S)
    assert read_ros_handshake_header(node.handed[0], io.BytesIO(), 4096) == header
    assert node.handed[0].recv(100) == b"next"


@pytest.mark.parametrize("sent", [0, 2, 6])
def test_a_connection_closed_mid_header_is_closed_at_once(node, sent):
    client = node.connection()
    client.sendall(HEADER[:sent])
    client.close()
    assert wait_for(lambda: node.warnings, DEADLINE_S) == [
        "inbound TCPROS connections closed before their header arrived (at most one warning per 10 s): "
        "1 closed by the client"]
    assert node.headers.waiting() == 0 and node.handed == []


def test_a_header_not_complete_in_time_is_closed():
    n = Node(timeout_s=0.2)
    try:
        client = n.connection()
        client.sendall(HEADER[:5])
        assert wait_for(lambda: closed(client), DEADLINE_S)
        assert n.warnings == ["inbound TCPROS connections closed before their header arrived (at most one "
                              "warning per 10 s): 1 no header within 0 s"]
    finally:
        n.headers.close()


def test_too_long_a_header_is_refused():
    n = Node(max_header_bytes=100)
    try:
        client = n.connection()
        client.sendall(struct.pack("<I", 97))
        assert wait_for(lambda: closed(client), DEADLINE_S)
        assert "1 header over 100 bytes" in n.warnings[0]
    finally:
        n.headers.close()


def test_an_empty_header_is_refused(node):
    """rospy's own read would wait for a byte after the length, on its handler's thread, forever."""
    client = node.connection(struct.pack("<I", 0))
    assert wait_for(lambda: closed(client), DEADLINE_S)
    assert "1 empty header" in node.warnings[0] and node.handed == []


def test_past_the_bound_the_oldest_are_closed_with_one_warning_and_a_new_client_gets_through():
    n = Node(max_waiting=3)
    try:
        clients = [n.connection(HEADER[:2]) for _ in range(6)]
        assert wait_for(lambda: all(closed(c) for c in clients[:3]), DEADLINE_S)
        assert n.headers.waiting() == 3 and not any(closed(c) for c in clients[3:])
        assert len(n.warnings) == 1 and "oldest over the bound of 3 waiting" in n.warnings[0]
        newcomer = n.connection()
        newcomer.sendall(HEADER)
        assert n.handed_on.wait(DEADLINE_S) and n.handed[0].recv(4096) == HEADER
        for client in clients + [newcomer]:
            client.close()
        assert wait_for(lambda: n.headers.waiting() == 0, DEADLINE_S)
        assert len(n.warnings) == 1  # the next comes after WARN_PERIOD_S, with the count since
    finally:
        n.headers.close()


def test_waiting_connections_do_not_wake_the_thread(node):
    """Its thread wakes for what happens (a connection, bytes, an end), never to look again."""
    clients = [node.connection(HEADER[:2]) for _ in range(50)]
    assert wait_for(lambda: node.headers.waiting() == 50 and node.headers.buffered() == 100, DEADLINE_S)
    before = node.headers.wakeups
    node.connection().sendall(HEADER)  # one connection, then its header: two events
    assert node.handed_on.wait(DEADLINE_S)
    # and at most one for the last wake-up byte of the 50 connections, if still unread
    assert node.headers.wakeups - before <= 3
    for client in clients:
        client.close()
    assert wait_for(lambda: node.headers.waiting() == 0, DEADLINE_S)


def test_close_closes_what_waits():
    n = Node()
    client = n.connection()
    assert wait_for(lambda: n.headers.waiting() == 1, DEADLINE_S)
    n.headers.close()
    assert closed(client)
    late = n.connection()
    assert wait_for(lambda: closed(late), DEADLINE_S)
