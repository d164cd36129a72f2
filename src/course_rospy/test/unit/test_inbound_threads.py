"""inbound_threads.header_arrived: True once a whole TCPROS header (or the end of the connection)
waits on the socket, False when the deadline passes first; nothing is consumed."""
import socket
import struct

from course_rospy import inbound_threads

HEADER = b"callerid=/x"
FRAME = struct.pack("<I", len(HEADER) + 4) + struct.pack("<I", len(HEADER)) + HEADER


def test_a_whole_header_has_arrived_and_is_left_to_read():
    a, b = socket.socketpair()
    with a, b:
        b.sendall(FRAME)
        assert inbound_threads.header_arrived(a, 1.0)
        assert a.recv(1000) == FRAME


def test_an_idle_or_partial_connection_times_out():
    a, b = socket.socketpair()
    with a, b:
        assert not inbound_threads.header_arrived(a, 0.1)
        b.sendall(FRAME[:6])
        assert not inbound_threads.header_arrived(a, 0.2)
        b.sendall(FRAME[6:])
        assert inbound_threads.header_arrived(a, 1.0)


def test_a_closed_connection_is_handed_on():
    a, b = socket.socketpair()
    with a:
        b.close()
        assert inbound_threads.header_arrived(a, 1.0)
