"""A rospy node that one idle TCP connection cannot block: each inbound TCPROS connection's
header is awaited on a thread of its own, with a time limit.

rospy's TCPROS server (`rospy.impl.tcpros_base.TCPServer.run`) accepts connections on one
thread and, on that same thread, reads each new connection's handshake header
(`TCPROSServer._tcp_server_callback`) with a blocking socket and no time limit. So a single
client that connects and sends nothing (a port scanner, a student's half-written client, a
crashed node's half-open socket) holds the accept loop: every later subscriber of the node's
topics and every caller of its services waits until that connection closes. roscpp reads
headers asynchronously and does not block.

`install()` wraps `TCPROSServer._tcp_server_callback` (bound when the node's server starts, in
`init_node`): the accept thread hands each new socket to a daemon thread, which waits until the
whole header has arrived (peeked, not read: rospy's own code then reads it, unchanged, without
blocking) and then runs rospy's handler; a connection whose header has not arrived within
HEADER_TIMEOUT_S is closed. The socket stays blocking, as rospy's transports expect. Call it
before `rospy.init_node`.
"""
from __future__ import annotations

import select
import socket
import struct
import threading
import time

import rospy.impl.tcpros_base as tcpros_base

# Long enough for any client across a slow network (a header is one write after connect).
HEADER_TIMEOUT_S = 10.0
# While part of a header is in, look again this often (the socket stays readable meanwhile).
PARTIAL_POLL_S = 0.02
# A header announcing more than this is handed to rospy as it is (it would not fit a peek).
PEEK_MAX_BYTES = 1 << 20
_LENGTH = struct.Struct("<I")

_original_callback = tcpros_base.TCPROSServer._tcp_server_callback


def header_arrived(sock: socket.socket, timeout: float) -> bool:
    """Whether the whole handshake header (a 4-byte little-endian length, then that many bytes),
    or the end of the connection, is waiting on `sock` within `timeout` s. Nothing is read."""
    deadline = time.monotonic() + timeout
    poller = select.poll()
    poller.register(sock.fileno(), select.POLLIN | select.POLLPRI)
    want = _LENGTH.size
    while True:
        remaining = deadline - time.monotonic()
        if remaining <= 0 or not poller.poll(remaining * 1000):
            return False
        data = sock.recv(want, socket.MSG_PEEK)
        if not data:
            return True  # closed by the peer: rospy's read says so in its own words
        if len(data) >= _LENGTH.size and want == _LENGTH.size:
            size = _LENGTH.unpack_from(data)[0]
            if size + _LENGTH.size > PEEK_MAX_BYTES:
                return True
            want = _LENGTH.size + size
            continue
        if len(data) >= want:
            return True
        time.sleep(PARTIAL_POLL_S)


def _serve(server: tcpros_base.TCPROSServer, sock: socket.socket, client_addr) -> None:
    try:
        arrived = header_arrived(sock, HEADER_TIMEOUT_S)
    except OSError:
        arrived = False
    if not arrived:
        tcpros_base.logwarn("inbound TCPROS connection from %s:%s sent no header within %.0f s: closed"
                            % (client_addr[0], client_addr[1], HEADER_TIMEOUT_S))
        sock.close()
        return
    _original_callback(server, sock, client_addr)


def _callback(self: tcpros_base.TCPROSServer, sock: socket.socket, client_addr) -> None:
    threading.Thread(target=_serve, args=(self, sock, client_addr), name="tcpros-inbound", daemon=True).start()


def install() -> None:
    """From now on, every TCPROS server this process starts awaits each inbound header on a
    thread of its own (see the module docstring)."""
    tcpros_base.TCPROSServer._tcp_server_callback = _callback


def uninstall() -> None:
    """rospy's own behaviour again (for tests)."""
    tcpros_base.TCPROSServer._tcp_server_callback = _original_callback
