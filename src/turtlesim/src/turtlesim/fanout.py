"""Publishing from the 62.5 Hz tick without a thread per subscriber.

A rospy publisher made with `queue_size` gives every subscriber connection a thread of its
own (rospy's QueuedConnection): each publish queues the message, wakes that thread and
yields the GIL (`time.sleep(0)`), and the thread then writes the socket. With 50 turtles
whose poses are all watched that is 3,125 thread hand-overs a second, and it was most of
turtlesim's CPU (docs/turtlesim_performance.md).

`write_from_publisher` keeps the queue's one promise, that a subscriber which stops
reading never holds the publisher up, without the threads: the publishing thread writes
each connection's socket itself, without blocking. When a socket is full (a suspended
`rostopic echo`), the connection keeps the unsent tail of the message the socket took part
of, and behind it only the newest whole message, which is what `queue_size=1` keeps; both
go out on later publishes. That suits topics published on a heartbeat, like turtlesim's
poses: nothing is left waiting for longer than a tick.

`TickPublisher` goes one step further for the heartbeat's own small messages (a pose, a
colour): it packs the fields straight into the bytes TCPROS sends (the 4-byte length and the
message's struct), once per publish, and skips all of it when nobody subscribes.
"""
from __future__ import annotations

import struct
from typing import Optional, Type

import rospy
from rospy.exceptions import TransportTerminated


class NonBlockingConnection:
    """One subscriber's connection, written without blocking (stands where QueuedConnection would).

    Every attribute but `write_data` is the wrapped transport's, so rospy's bookkeeping (ids,
    stats, close, fileno) sees the transport it made.
    """

    def __init__(self, transport) -> None:
        self._transport = transport
        self._unsent = memoryview(b"")  # the tail of a message the socket took only part of
        self._newest: Optional[bytes] = None  # the newest whole message waiting behind it
        if transport.socket is not None:
            transport.socket.setblocking(False)

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self._transport, name)

    def write_data(self, data: bytes) -> bool:
        """Send `data` as far as the socket takes it now; what it does not take waits for the next call."""
        if self._transport.done:
            raise TransportTerminated("connection closed")
        self._newest = data  # an older whole message still waiting is dropped, as queue_size=1 drops it
        self._flush()
        return True

    @property
    def backlog(self) -> int:
        """Bytes waiting for the subscriber to read (0 when it keeps up)."""
        return len(self._unsent) + (len(self._newest) if self._newest is not None else 0)

    def _flush(self) -> None:
        if self._unsent:
            self._unsent = self._write(self._unsent)
            if self._unsent:
                return  # the socket is still full: the newest waits whole
        if self._newest is not None:
            data, self._newest = self._newest, None
            rest = self._write(memoryview(data))
            if len(rest) == len(data):
                self._newest = data  # none of it went: still whole, so a newer one may replace it
            else:
                self._unsent = rest

    def _write(self, data: memoryview) -> memoryview:
        """Send what the socket takes of `data`; the rest."""
        sent = self._send(data)
        self._transport.stat_bytes += sent
        if sent == len(data):
            self._transport.stat_num_msg += 1
        return data[sent:]

    def _send(self, data: memoryview) -> int:
        sock = self._transport.socket
        if sock is None:  # closed by another thread (the subscriber went away)
            raise TransportTerminated("connection closed")
        try:
            return sock.send(data)
        except (BlockingIOError, InterruptedError):
            return 0
        except OSError as err:  # EPIPE, ECONNRESET, EBADF after a close: the subscriber is gone
            self._transport.close()
            raise TransportTerminated(str(err)) from err


def write_from_publisher(pub: rospy.Publisher) -> rospy.Publisher:
    """Make the connections `pub` gets from now on NonBlockingConnections written by the
    publishing thread, instead of a queue and a thread each. Returns `pub`."""
    impl = pub.impl
    with impl.c_lock:
        impl.queue_size = None  # no QueuedConnection around new connections
        add_connection = impl.add_connection
        impl.add_connection = lambda c: add_connection(NonBlockingConnection(c))
    return pub


class Wire:
    """A message of fixed size made of plain fields, as TCPROS sends it: its size in 4 bytes,
    then the struct genpy's serialize() packs (`layout`, e.g. "<5f" for turtlesim/Pose)."""

    def __init__(self, layout: str) -> None:
        self._struct = struct.Struct("<I" + layout.lstrip("<"))
        self._size = self._struct.size - 4

    def pack(self, *fields) -> bytes:
        """The message with these field values (in .msg order)."""
        return self._struct.pack(self._size, *fields)


class TickPublisher:
    """A topic the tick publishes: a rospy publisher for registration and connections, and a
    fast path for the message bytes.

    `layout` is the message's struct (see Wire).
    """

    def __init__(self, name: str, data_class: Type, layout: str) -> None:
        self._pub = write_from_publisher(rospy.Publisher(name, data_class, queue_size=1))
        self._wire = Wire(layout)

    def has_subscribers(self) -> bool:
        impl = self._pub.impl
        return impl is not None and bool(impl.connections)

    def publish(self, *fields) -> None:
        """Send the message with these field values (in .msg order) to every subscriber."""
        impl = self._pub.impl
        if impl is None or impl.closed or not impl.connections:
            return
        data = self._wire.pack(*fields)
        gone = []
        for conn in impl.connections:
            try:
                conn.write_data(data)
            except Exception:  # noqa: BLE001  (rospy drops such a connection the same way)
                gone.append(conn)
        impl.message_data_sent += len(data)
        for conn in gone:
            try:
                conn.close()  # rospy's close callback removes it from the topic
            except Exception:  # noqa: BLE001
                pass

    def unregister(self) -> None:
        self._pub.unregister()
