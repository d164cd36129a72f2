"""course_web.service_probe against sockets of its own: a node that answers the probe with its
header, one that hangs up, an address nothing listens on, an address that is not rosrpc://. (A real
service's node: test_lab_view_lazy.)"""
from __future__ import annotations

import socket
import threading
from typing import Dict, List, Optional

import pytest
import rosgraph.network

from course_web.service_probe import ServiceProbeError, address, probe_header, service_type

TIMEOUT_S = 5.0


class OneShotNode:
    """A listening socket that takes one connection, reads the header sent to it and answers
    `answer` (a header), or hangs up at once (None)."""

    def __init__(self, answer: Optional[Dict[str, str]]) -> None:
        self.answer = answer
        self.received: List[bytes] = []
        self.server = socket.create_server(("127.0.0.1", 0))
        self.uri = "rosrpc://127.0.0.1:%d" % self.server.getsockname()[1]
        self.thread = threading.Thread(target=self.serve, daemon=True)
        self.thread.start()

    def serve(self) -> None:
        connection, _ = self.server.accept()
        with connection:
            connection.settimeout(TIMEOUT_S)
            if self.answer is None:
                return
            self.received.append(connection.recv(4096))
            connection.sendall(rosgraph.network.encode_ros_handshake_header(self.answer))

    def close(self) -> None:
        self.thread.join(TIMEOUT_S)
        self.server.close()

    def __enter__(self) -> "OneShotNode":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def test_the_node_says_its_type_to_a_probe():
    with OneShotNode({"type": "std_srvs/Trigger", "md5sum": "937c9679a518e3a18d831e57125ea522",
                     "callerid": "/turtlesim"}) as node:
        assert service_type("/turtlesim/canvas", node.uri, "/course_web", TIMEOUT_S) == "std_srvs/Trigger"
    sent = node.received[0]
    for field in (b"probe=1", b"md5sum=*", b"callerid=/course_web", b"service=/turtlesim/canvas"):
        assert field in sent


def test_a_header_without_a_type_is_an_error():
    with OneShotNode({"callerid": "/somebody"}) as node:
        assert probe_header("/s", node.uri, "/course_web", TIMEOUT_S) == {"callerid": "/somebody"}
    with OneShotNode({"callerid": "/somebody"}) as node:
        with pytest.raises(ServiceProbeError, match="did not say its type"):
            service_type("/s", node.uri, "/course_web", TIMEOUT_S)


def test_a_node_that_hangs_up_is_an_error():
    with OneShotNode(None) as node:
        with pytest.raises(ServiceProbeError, match="/s at rosrpc://127.0.0.1:[0-9]+ does not answer"):
            service_type("/s", node.uri, "/course_web", TIMEOUT_S)


def test_nothing_listening_and_a_bad_address_are_errors():
    with socket.create_server(("127.0.0.1", 0)) as taken:
        port = taken.getsockname()[1]
    with pytest.raises(ServiceProbeError, match="does not answer"):
        service_type("/s", "rosrpc://127.0.0.1:%d" % port, "/course_web", TIMEOUT_S)
    for uri in ("http://127.0.0.1:1234", "rosrpc://127.0.0.1", "rosrpc://host:port", "rosrpc://[::1:5", ""):
        with pytest.raises(ServiceProbeError, match="not rosrpc://host:port"):
            service_type("/s", uri, "/course_web", TIMEOUT_S)


def test_rosrpc_addresses_as_the_master_gives_them():
    assert address("rosrpc://localhost:40111") == ("localhost", 40111)
    assert address("rosrpc://lab-pc.local:5/") == ("lab-pc.local", 5)
    assert address("rosrpc://[::1]:40111") == ("::1", 40111)
