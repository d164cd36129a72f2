"""A rospy node that hostile or broken TCP clients cannot block or exhaust: every inbound TCPROS
connection whose handshake header has not fully arrived waits in one selector thread per node,
with a time limit and a bound on how many may wait at once.

rospy's TCPROS server (`rospy.impl.tcpros_base.TCPServer.run`) accepts connections on one thread
and, on that same thread, reads each new connection's header (`TCPROSServer._tcp_server_callback`)
with a blocking socket and no time limit: one client that connects and sends nothing holds every
later subscriber and service caller of the node (slowloris). A thread per waiting connection
(this module's first form) moved the problem: each half-sent header kept a thread polling it, a
closed one for the whole time limit, and nothing bounded how many waited.

Here (as roscpp does) nothing waits on a thread of its own. `install()` replaces
`TCPROSServer._tcp_server_callback` (bound when the node's server starts, in `init_node`): the
accept thread only hands the new socket to the node's `WaitingHeaders`, whose one thread reads
(consumes) each connection's bytes into a buffer as they come, so a connection closed by its peer
is seen at once, whatever part of the header it sent. A header not complete within
HEADER_TIMEOUT_S is closed; past MAX_WAITING_HEADERS waiting at once, the oldest is closed; each
with a throttled warning. A complete header goes, with its socket, to rospy's own handler on a
short-lived thread; the socket (a `ReplaySocket`) returns the header's bytes to rospy's first
reads, and nothing past the header was read, so rospy reads exactly what the client sent.

Cost to the node while clients misbehave: one thread, one epoll and a socket pair, plus at most
MAX_WAITING_HEADERS sockets and MAX_WAITING_HEADERS * MAX_HEADER_BYTES of buffers; an idle or
half-sent header costs no CPU until its client sends again or its time runs out.
Call `install()` before `rospy.init_node`.
"""
from __future__ import annotations

import collections
import functools
import selectors
import socket
import struct
import threading
import time
from dataclasses import dataclass, field
from typing import Callable, Deque, Dict, Optional, Tuple

import rospy.core
import rospy.impl.tcpros_base as tcpros_base

# Long enough for any client across a slow network (a header is one write after connect).
HEADER_TIMEOUT_S = 10.0
# Headers waiting at once, per node: far more than the clients that connect in one header's time
# (every subscriber of a topic at start-up), few enough that the node's open files stay below
# this + its own under any number of half-sent headers (the default limit is 1024).
MAX_WAITING_HEADERS = 128
# A longer header is refused: real ones are a few KB (the largest, a message definition, tens).
MAX_HEADER_BYTES = 256 * 1024
# Connections the kernel completes before the accept thread takes them (rospy listens with 5: a
# client opening connections faster than the accept thread runs saw its SYN dropped and sent
# again 1 s later, a burst of 300 took 13 s).
ACCEPT_BACKLOG = 128
# At most one warning per this many seconds about connections closed before their header.
WARN_PERIOD_S = 10.0

_LENGTH = struct.Struct("<I")
_READ_BYTES = 65536
_ATTRIBUTE = "_course_waiting_headers"

Address = Tuple


class ReplaySocket(socket.socket):
    """A connected socket whose first reads return bytes already read from it, then its own."""

    _replay = b""

    @classmethod
    def take_over(cls, sock: socket.socket, already_read: bytes) -> "ReplaySocket":
        """The same connection as `sock` (which is detached, not closed), blocking, as rospy's
        transports expect."""
        replay = cls(sock.family, sock.type, sock.proto, fileno=sock.detach())
        replay.settimeout(None)
        replay._replay = already_read
        return replay

    def recv(self, bufsize: int, flags: int = 0) -> bytes:
        if not self._replay:
            return super().recv(bufsize, flags)
        data = self._replay[:bufsize]
        if not flags & socket.MSG_PEEK:
            self._replay = self._replay[bufsize:]
        return data


@dataclass
class _Waiting:
    sock: socket.socket
    address: Address
    deadline: float
    received: bytearray = field(default_factory=bytearray)

    def wanted(self) -> int:
        """How many more bytes complete the header (the length first, then what it announces)."""
        return _LENGTH.size + self.announced() - len(self.received)

    def announced(self) -> int:
        """The header's length as its first 4 bytes give it (0 until they have come)."""
        return _LENGTH.unpack_from(self.received)[0] if len(self.received) >= _LENGTH.size else 0


class WaitingHeaders:
    """Every inbound connection of one node until its header has arrived: one selector thread
    reads them all (see the module docstring). `hand_on(sock, address)` runs on a thread of its
    own for each complete header; `warn(text)` is called at most once per `warn_period_s`."""

    def __init__(self, hand_on: Callable[[socket.socket, Address], None], warn: Callable[[str], None],
                 timeout_s: float = HEADER_TIMEOUT_S, max_waiting: int = MAX_WAITING_HEADERS,
                 max_header_bytes: int = MAX_HEADER_BYTES, warn_period_s: float = WARN_PERIOD_S) -> None:
        self._hand_on = hand_on
        self._warn = warn
        self.timeout_s = timeout_s
        self.max_waiting = max_waiting
        self.max_header_bytes = max_header_bytes
        self.warn_period_s = warn_period_s
        self.wakeups = 0  # times the thread woke: stays put while waiting clients send nothing
        self._selector = selectors.DefaultSelector()
        self._wake_in, self._wake_out = socket.socketpair()
        for end in (self._wake_in, self._wake_out):
            end.setblocking(False)
        self._selector.register(self._wake_in, selectors.EVENT_READ)
        self._incoming: Deque[Tuple[socket.socket, Address]] = collections.deque()
        self._waiting: Dict[int, _Waiting] = {}  # by file descriptor, oldest first
        self._closed_early: collections.Counter = collections.Counter()
        self._last_warning = float("-inf")
        self._closing = False
        self._thread = threading.Thread(target=self._run, name="tcpros-headers", daemon=True)
        self._thread.start()

    def add(self, sock: socket.socket, address: Address) -> None:
        """Wait for `sock`'s header (any thread; returns at once)."""
        if self._closing:
            sock.close()
            return
        self._incoming.append((sock, address))
        self._wake()

    def waiting(self) -> int:
        """Connections whose header has not arrived (taken in by the thread so far)."""
        return len(self._waiting)

    def buffered(self) -> int:
        """Bytes read so far from the connections that wait."""
        return sum(len(w.received) for w in list(self._waiting.values()))

    def close(self) -> None:
        """Stop the thread and close every connection still waiting."""
        self._closing = True
        self._wake()
        self._thread.join()

    def _wake(self) -> None:
        try:
            self._wake_out.send(b"\0")
        except (BlockingIOError, OSError):
            pass  # already woken (the pair's buffer is full), or closing

    def _run(self) -> None:
        try:
            while not self._closing:
                timeout = None
                if self._waiting:
                    timeout = max(0.0, next(iter(self._waiting.values())).deadline - time.monotonic())
                for key, _ in self._selector.select(timeout):
                    if key.fileobj is self._wake_in:
                        self._drain_wake()
                    elif key.fd in self._waiting:
                        self._read(self._waiting[key.fd])
                self.wakeups += 1
                self._take_in()
                self._expire()
        finally:
            for waiting in list(self._waiting.values()):
                self._drop(waiting, None)
            while self._incoming:
                self._incoming.popleft()[0].close()
            self._selector.close()
            self._wake_in.close()
            self._wake_out.close()

    def _drain_wake(self) -> None:
        try:
            while self._wake_in.recv(4096):
                pass
        except BlockingIOError:
            pass

    def _take_in(self) -> None:
        while self._incoming:
            sock, address = self._incoming.popleft()
            try:
                sock.setblocking(False)
                waiting = _Waiting(sock, address, time.monotonic() + self.timeout_s)
                self._selector.register(sock, selectors.EVENT_READ)
            except (OSError, ValueError):
                sock.close()
                continue
            self._waiting[sock.fileno()] = waiting
            while len(self._waiting) > self.max_waiting:
                self._drop(next(iter(self._waiting.values())), "oldest over the bound of %d waiting" % self.max_waiting)

    def _expire(self) -> None:
        now = time.monotonic()
        while self._waiting:
            oldest = next(iter(self._waiting.values()))
            if oldest.deadline > now:
                return
            self._drop(oldest, "no header within %.0f s" % self.timeout_s)

    def _read(self, waiting: _Waiting) -> None:
        try:
            data = waiting.sock.recv(min(waiting.wanted(), _READ_BYTES))
        except BlockingIOError:
            return
        except OSError:
            data = b""
        if not data:
            self._drop(waiting, "closed by the client")
            return
        waiting.received += data
        if waiting.announced() + _LENGTH.size > self.max_header_bytes:
            self._drop(waiting, "header over %d bytes" % self.max_header_bytes)
        elif len(waiting.received) == _LENGTH.size and waiting.announced() == 0:
            # rospy would wait for more than the length before it parses: on its thread, forever
            self._drop(waiting, "empty header")
        elif waiting.wanted() == 0:
            self._forget(waiting)
            try:
                sock = ReplaySocket.take_over(waiting.sock, bytes(waiting.received))
            except OSError:
                waiting.sock.close()
                return
            threading.Thread(target=self._hand_on, args=(sock, waiting.address), name="tcpros-handshake",
                             daemon=True).start()

    def _forget(self, waiting: _Waiting) -> None:
        del self._waiting[waiting.sock.fileno()]
        self._selector.unregister(waiting.sock)

    def _drop(self, waiting: _Waiting, reason: Optional[str]) -> None:
        self._forget(waiting)
        waiting.sock.close()
        if reason:
            self._closed_early[reason] += 1
            now = time.monotonic()
            if now - self._last_warning >= self.warn_period_s:
                self._last_warning = now
                self._warn("inbound TCPROS connections closed before their header arrived (at most one "
                           "warning per %.0f s): %s" % (self.warn_period_s, ", ".join(
                               "%d %s" % (n, why) for why, n in sorted(self._closed_early.items()))))
                self._closed_early.clear()


_original_callback = tcpros_base.TCPROSServer._tcp_server_callback


def _callback(self: tcpros_base.TCPROSServer, sock: socket.socket, client_addr: Address) -> None:
    """The accept thread's handler: the node's WaitingHeaders takes the connection over."""
    waiting = getattr(self, _ATTRIBUTE, None)
    if waiting is None:  # only the server's accept thread gets here: no race
        waiting = WaitingHeaders(functools.partial(_original_callback, self), rospy.core.logwarn)
        setattr(self, _ATTRIBUTE, waiting)
        try:
            self.tcp_ros_server.server_sock.listen(ACCEPT_BACKLOG)
        except (AttributeError, OSError) as e:  # rospy's backlog stays: slower bursts, no harm
            rospy.core.logwarn("TCPROS server: backlog stays rospy's: %s" % e)
    waiting.add(sock, client_addr)


def install() -> None:
    """From now on, every TCPROS server this process starts waits for inbound headers in one
    selector thread (see the module docstring)."""
    tcpros_base.TCPROSServer._tcp_server_callback = _callback


def uninstall() -> None:
    """rospy's own behaviour again (for tests)."""
    tcpros_base.TCPROSServer._tcp_server_callback = _original_callback
