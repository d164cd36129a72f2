"""A bare TCPROS client (no rospy node in the test process): find a node's TCPROS port, hold an
idle connection to it, take one message of a topic from it, call one of its services.

For tests of what a node does with its inbound connections (course_rospy.inbound_headers): every
call has a deadline and raises socket.timeout (an OSError) past it, so a blocked node fails the
test instead of hanging it.
"""
from __future__ import annotations

import io
import socket
import struct
import xmlrpc.client
from typing import Optional, Tuple, Type
from urllib.parse import urlparse

from rosgraph.network import read_ros_handshake_header, write_ros_handshake_header

CALLER_ID = "/course_testkit_tcpros"
BUFF_SIZE = 65536
_LENGTH = struct.Struct("<I")


def _ok(answer: list, what: str):
    code, message, value = answer
    if code != 1:
        raise LookupError("%s: %s" % (what, message))
    return value


def node_api(master_uri: str, node: str) -> str:
    """`node`'s XML-RPC URI, as the master has it (LookupError when it has none)."""
    return _ok(xmlrpc.client.ServerProxy(master_uri).lookupNode(CALLER_ID, node), "lookupNode " + node)


def topic_address(master_uri: str, node: str, topic: str) -> Tuple[str, int]:
    """The (host, port) of `node`'s TCPROS server for `topic`, as the node itself hands it out."""
    api = node_api(master_uri, node)
    protocol = _ok(xmlrpc.client.ServerProxy(api).requestTopic(CALLER_ID, topic, [["TCPROS"]]),
                   "requestTopic " + topic)
    return protocol[1], int(protocol[2])


def service_address(master_uri: str, service: str) -> Tuple[str, int]:
    uri = urlparse(_ok(xmlrpc.client.ServerProxy(master_uri).lookupService(CALLER_ID, service),
                       "lookupService " + service))
    return uri.hostname, int(uri.port)


def _connect(address: Tuple[str, int], header: dict, timeout: float) -> Tuple[socket.socket, dict, io.BytesIO]:
    sock = socket.create_connection(address, timeout=timeout)
    try:
        write_ros_handshake_header(sock, dict(header, callerid=CALLER_ID))
        buff = io.BytesIO()
        answer = read_ros_handshake_header(sock, buff, BUFF_SIZE)
    except BaseException:
        sock.close()
        raise
    if "error" in answer:
        sock.close()
        raise ConnectionError("the node refused the connection: %s" % answer["error"])
    return sock, answer, buff


class _Reader:
    """Bytes of a connection in order: what the header read left over first, then the socket's."""

    def __init__(self, sock: socket.socket, buff: io.BytesIO) -> None:
        self.sock = sock
        self.pending = buff.getvalue()[:buff.tell()]

    def exactly(self, size: int) -> bytes:
        while len(self.pending) < size:
            chunk = self.sock.recv(BUFF_SIZE)
            if not chunk:
                raise ConnectionError("the node closed the connection")
            self.pending += chunk
        data, self.pending = self.pending[:size], self.pending[size:]
        return data


def receive_one(address: Tuple[str, int], topic: str, msg_class: Type, timeout: float):
    """Subscribe `topic` at the publisher's `address` and return its first message."""
    sock, _, buff = _connect(address, {"topic": topic, "md5sum": msg_class._md5sum, "type": msg_class._type,
                                       "tcp_nodelay": "1"}, timeout)
    with sock:
        reader = _Reader(sock, buff)
        body = reader.exactly(_LENGTH.unpack(reader.exactly(_LENGTH.size))[0])
    return msg_class().deserialize(body)


def call(address: Tuple[str, int], service: str, srv_class: Type, request, timeout: float):
    """Call `service` at its server's `address` once and return the response (LookupError when
    the server answers with an error)."""
    sock, _, buff = _connect(address, {"service": service, "md5sum": srv_class._md5sum}, timeout)
    with sock:
        out = io.BytesIO()
        request.serialize(out)
        sock.sendall(_LENGTH.pack(len(out.getvalue())) + out.getvalue())
        reader = _Reader(sock, buff)
        ok = reader.exactly(1)[0]
        body = reader.exactly(_LENGTH.unpack(reader.exactly(_LENGTH.size))[0])
    if not ok:
        raise LookupError("the service answered with an error: %s" % body.decode("utf-8", "replace"))
    return srv_class._response_class().deserialize(body)


def address_or_none(master_uri: str, node: str, topic: str) -> Optional[Tuple[str, int]]:
    """topic_address, or None while the node or its topic is not up yet (to wait on)."""
    try:
        return topic_address(master_uri, node, topic)
    except (OSError, LookupError):
        return None


def service_address_or_none(master_uri: str, service: str) -> Optional[Tuple[str, int]]:
    """service_address, or None while the service is not up yet (to wait on)."""
    try:
        return service_address(master_uri, service)
    except (OSError, LookupError):
        return None
