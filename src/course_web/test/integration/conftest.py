"""A live lab for the integration tests: a private master, turtlesim (canvas at 30 fps) and
lab_view on a free port (or on the master through a relay that counts lab_view's calls); and a
small websocket client to talk to it.

The test process itself never becomes a ROS node: it sees ROS only through the server, the
way a browser does, so any number of these tests can share one pytest process.
"""
from __future__ import annotations

import asyncio
import collections
import json
import socketserver
import threading
import time
import urllib.error
import urllib.request
import xmlrpc.client
import xmlrpc.server
from typing import Any, Callable, Counter, Dict, List, Optional

import pytest
from tornado.websocket import WebSocketClientConnection, websocket_connect

from course_testkit.browser import TIMEOUT_S as BROWSER_TIMEOUT_S, chromium
from course_checks.isolation import free_port
from course_testkit.master import PrivateMaster
from course_checks.nodes import NodeProcess, find_executable
from course_checks.waiting import wait_for

STARTUP_TIMEOUT_S = 60.0
IMAGE_RATE = 30
TEST_MESSAGE_LIMIT = 200_000
"""lab_view's --max-message-bytes in these tests: small, so the oversized frame is quick to send."""


def http_status(url: str, headers: Optional[Dict[str, str]] = None) -> Optional[int]:
    """The HTTP status of a GET (None when nothing answers)."""
    try:
        with urllib.request.urlopen(urllib.request.Request(url, headers=headers or {}), timeout=10) as reply:
            return reply.status
    except urllib.error.HTTPError as err:
        return err.code
    except OSError:
        return None


def turtlesim_command() -> List[str]:
    return [find_executable("turtlesim", "turtlesim_node"), "_image_rate:=%d" % IMAGE_RATE]


class Lab:
    """The running lab: its master, turtlesim and one lab_view (`env`: lab_view's environment,
    instead of the master's)."""

    def __init__(self, master: PrivateMaster, env: Optional[Dict[str, str]] = None) -> None:
        self.master = master
        self.turtlesim = master.start(turtlesim_command(), "turtlesim")
        self.port = free_port()
        self.message_limit = TEST_MESSAGE_LIMIT
        self.server = self.start_server(self.port, env=env)

    def start_server(self, port: int, *extra: str, env: Optional[Dict[str, str]] = None) -> NodeProcess:
        """lab_view on `port` (`env`: instead of the master's environment)."""
        command = [find_executable("course_web", "lab_view"), "--port", str(port),
                   "--max-message-bytes", str(TEST_MESSAGE_LIMIT), *extra]
        node = self.master.start(command, "lab_view-%d" % port, env)
        if not wait_for(lambda: "lab_view: open" in node.output() or not node.running(), STARTUP_TIMEOUT_S) \
                or not node.running():
            raise AssertionError("lab_view did not start:\n%s" % node.output()[-3000:])
        return node

    def url(self, path: str = "/", port: Optional[int] = None) -> str:
        return "http://127.0.0.1:%d%s" % (port or self.port, path)

    def status(self, path: str = "/", port: Optional[int] = None, **headers: str) -> Optional[int]:
        return http_status(self.url(path, port), {k.replace("_", "-"): v for k, v in headers.items()})

    def ws_url(self, port: Optional[int] = None, token: Optional[str] = None) -> str:
        return "ws://127.0.0.1:%d/websocket%s" % (port or self.port, "?token=%s" % token if token else "")


@pytest.fixture(scope="module")
def lab():
    with PrivateMaster() as master:
        yield Lab(master)


@pytest.fixture
def lab_on():
    """Lab(master): for a test that runs a master of its own."""
    return Lab


@pytest.fixture
def turtlesim():
    """The command that starts turtlesim as the lab does."""
    return turtlesim_command()


class _ThreadingXmlRpcServer(socketserver.ThreadingMixIn, xmlrpc.server.SimpleXMLRPCServer):
    daemon_threads = True


class CountingRelay:
    """The master's XML-RPC API on a port of its own, each call passed on and counted by method:
    a node pointed at it (its ROS_MASTER_URI) shows the test everything it asks the master."""

    def __init__(self, master_uri: str) -> None:
        self.master_uri = master_uri
        self.lock = threading.Lock()
        self.calls: Counter[str] = collections.Counter()
        self.server = _ThreadingXmlRpcServer(("127.0.0.1", 0), logRequests=False)
        self.server.register_instance(self)
        self.uri = "http://127.0.0.1:%d/" % self.server.server_address[1]
        threading.Thread(target=self.server.serve_forever, name="counting-relay", daemon=True).start()

    def _dispatch(self, method: str, params: tuple) -> Any:
        with self.lock:
            self.calls[method] += 1
        return getattr(xmlrpc.client.ServerProxy(self.master_uri), method)(*params)

    def counted(self) -> Counter[str]:
        with self.lock:
            return collections.Counter(self.calls)

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()


@pytest.fixture(scope="module")
def counted_lab():
    """A lab whose lab_view asks its master through a CountingRelay (`lab.relay`)."""
    with PrivateMaster() as master:
        relay = CountingRelay(master.uri)
        try:
            counted = Lab(master, env=dict(master.env, ROS_MASTER_URI=relay.uri))
            counted.relay = relay
            yield counted
        finally:
            relay.close()


class SimulatorLab(Lab):
    """003 Part II's world instead of turtlesim: RRBot (headless), a coke can spawned as the text
    does, and lab_view."""

    def __init__(self, master: PrivateMaster) -> None:
        self.master = master
        self.world = master.start(["roslaunch", "rrbot_gazebo", "rrbot_world.launch", "gui:=false"], "rrbot_world")
        self.can = master.start([find_executable("gazebo_ros", "spawn_model"), "-database", "coke_can", "-sdf",
                                 "-model", "coke_can", "-x", "1", "-z", "1"], "coke_can")
        self.port = free_port()
        self.message_limit = TEST_MESSAGE_LIMIT
        self.server = self.start_server(self.port)


@pytest.fixture(scope="module")
def sim_lab():
    with PrivateMaster() as master:
        yield SimulatorLab(master)


class Client:
    """A rosbridge client for tests: send ops, read replies (binary image frames are kept apart)."""

    def __init__(self, connection: WebSocketClientConnection) -> None:
        self.connection = connection
        self.images: List[bytes] = []

    @classmethod
    async def connect(cls, url: str) -> "Client":
        return cls(await websocket_connect(url, max_message_size=64 * 1024 * 1024))

    def send(self, **op: Any) -> None:
        self.connection.write_message(json.dumps(op))

    def send_raw(self, text: str) -> None:
        self.connection.write_message(text)

    async def receive(self, timeout: float) -> Optional[Dict[str, Any]]:
        """The next JSON message, or None at the deadline (or when the socket closed)."""
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            try:
                message = await asyncio.wait_for(self.connection.read_message(), left)
            except asyncio.TimeoutError:
                return None
            if message is None:
                return None
            if isinstance(message, bytes):
                self.images.append(message)
                continue
            return json.loads(message)

    async def expect(self, predicate: Callable[[Dict[str, Any]], bool], timeout: float = 20.0,
                     what: str = "a message") -> Dict[str, Any]:
        """The first message that satisfies `predicate`; fails after `timeout`."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            message = await self.receive(deadline - time.monotonic())
            if message is not None and predicate(message):
                return message
        raise AssertionError("no %s within %.0f s" % (what, timeout))

    def close(self) -> None:
        self.connection.close()


def is_error(message: Dict[str, Any]) -> bool:
    return message.get("op") == "status" and message.get("level") == "error"


@pytest.fixture
def client_class():
    return Client


@pytest.fixture
def error_check():
    return is_error


# ---- a real browser ------------------------------------------------------------------------
@pytest.fixture(scope="module")
def browser():
    """Headless Debian chromium (course_testkit.browser), one per test module."""
    with chromium() as driver:
        yield driver


def open_lab_page(driver, lab: Lab) -> None:
    """Load the page and wait until its websocket is open."""
    driver.get(lab.url("/"))
    connected = wait_for(lambda: driver.execute_script(
        "return document.body.dataset.ready === 'true' && "
        "document.getElementById('connection').dataset.state === 'open'"), BROWSER_TIMEOUT_S)
    assert connected, "the page did not connect: %s" % driver.execute_script(
        "return document.getElementById('connection').textContent")


@pytest.fixture
def open_page():
    return open_lab_page
