"""NonBlockingConnection: written by the publishing thread, never blocking it, keeping what
queue_size=1 keeps when the subscriber does not read. Real sockets (a socketpair); the
transport around them is the few attributes rospy's TCPROSTransport offers it."""
import io
import socket

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rospy.exceptions import TransportTerminated
from rospy.msg import serialize_message

from turtlesim.fanout import NonBlockingConnection, Wire
from turtlesim.msg import Color, Pose
from turtlesim.node import COLOR_LAYOUT, POSE_LAYOUT

MESSAGE = 28  # a turtlesim/Pose on the wire: 4 bytes of length, 5 float32


class Transport:
    """What NonBlockingConnection uses of rospy's TCPROSTransport."""

    def __init__(self, sock: socket.socket) -> None:
        self.socket = sock
        self.done = False
        self.stat_bytes = 0
        self.stat_num_msg = 0
        self.endpoint_id = "/subscriber"

    def close(self) -> None:
        self.done = True
        self.socket.close()
        self.socket = None


@pytest.fixture
def pair():
    ours, theirs = socket.socketpair()
    ours.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    theirs.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    yield ours, theirs
    for s in (ours, theirs):
        s.close()


def message(i: int) -> bytes:
    return i.to_bytes(4, "little") * (MESSAGE // 4)


def read_all(sock: socket.socket) -> bytes:
    sock.setblocking(False)
    data = b""
    while True:
        try:
            chunk = sock.recv(65536)
        except BlockingIOError:
            return data
        if not chunk:
            return data
        data += chunk


def test_a_reading_subscriber_gets_every_message_in_order(pair):
    ours, theirs = pair
    conn = NonBlockingConnection(Transport(ours))
    for i in range(10):
        assert conn.write_data(message(i))
    assert read_all(theirs) == b"".join(message(i) for i in range(10))
    assert conn.stat_num_msg == 10 and conn.stat_bytes == 10 * MESSAGE and conn.backlog == 0


def test_a_subscriber_that_stops_reading_never_blocks_and_later_gets_whole_messages_then_the_newest(pair):
    ours, theirs = pair
    conn = NonBlockingConnection(Transport(ours))
    written = 0
    while conn.backlog == 0:  # until the socket is full: each call returns at once
        conn.write_data(message(written))
        written += 1
        assert written < 100000, "the socket never filled"
    for i in range(written, written + 50):  # more while full: only the newest is kept
        conn.write_data(message(i))
    newest = written + 49
    assert conn.backlog < 2 * MESSAGE
    received = read_all(theirs)
    conn.write_data(message(newest + 1))  # the next publish sends the tail, then itself (the newest)
    received += read_all(theirs)
    assert len(received) % MESSAGE == 0, "a message was cut"
    numbers = [int.from_bytes(received[k:k + 4], "little") for k in range(0, len(received), MESSAGE)]
    assert numbers[-1] == newest + 1
    assert numbers[:-1] == sorted(numbers[:-1]) and len(set(numbers)) == len(numbers)
    assert set(numbers[:-1]) <= set(range(written)), "a message written while full went out before a newer one"
    assert conn.backlog == 0


def test_a_subscriber_gone_is_a_terminated_transport(pair):
    ours, theirs = pair
    transport = Transport(ours)
    conn = NonBlockingConnection(transport)
    theirs.close()
    with pytest.raises(TransportTerminated):
        for i in range(10):  # the first write may still be taken by the kernel
            conn.write_data(message(i))
    assert transport.done


def test_a_closed_transport_is_terminated_without_touching_the_socket(pair):
    ours, _ = pair
    transport = Transport(ours)
    conn = NonBlockingConnection(transport)
    transport.close()
    with pytest.raises(TransportTerminated):
        conn.write_data(message(1))


def test_everything_else_is_the_transports(pair):
    ours, _ = pair
    conn = NonBlockingConnection(Transport(ours))
    assert conn.endpoint_id == "/subscriber"
    with pytest.raises(AttributeError):
        conn.__missing__


FLOAT32 = st.floats(min_value=-3.4028234663852886e38, max_value=3.4028234663852886e38, allow_nan=False)


def genpy_bytes(msg) -> bytes:
    buff = io.BytesIO()
    serialize_message(buff, 0, msg)
    return buff.getvalue()


@pytest.mark.parametrize("msg_class, layout, field", [(Pose, POSE_LAYOUT, FLOAT32),
                                                       (Color, COLOR_LAYOUT, st.integers(0, 255))])
@settings(deadline=None)  # a first call may take a second on a loaded machine: no timing is asserted here
@given(data=st.data())
def test_a_tick_message_packs_to_the_bytes_genpy_sends(msg_class, layout, field, data):
    fields = data.draw(st.tuples(*[field] * len(msg_class.__slots__)))
    assert Wire(layout).pack(*fields) == genpy_bytes(msg_class(*fields))


def test_the_layouts_are_the_messages_own():
    assert Pose.__slots__ == ["x", "y", "theta", "linear_velocity", "angular_velocity"]
    assert Pose._slot_types == ["float32"] * 5
    assert Color.__slots__ == ["r", "g", "b"] and Color._slot_types == ["uint8"] * 3
