"""A ROS master stand-in that forwards every call to a real master and can hold chosen calls.

A node pointed at it (ROS_MASTER_URI=relay.uri) works as usual, except that a call the test
names (say registerService for /gazebo/pause_physics) waits in the relay until the test releases
it. The node is then blocked inside that call, holding whatever rospy holds there, and the test
can do what would otherwise need luck: interrupt the node at exactly that moment.
"""
from __future__ import annotations

import threading
import xmlrpc.client
from socketserver import ThreadingMixIn
from types import TracebackType
from typing import Callable, Optional, Tuple, Type
from xmlrpc.server import SimpleXMLRPCRequestHandler, SimpleXMLRPCServer

HOLD_TIMEOUT_S = 60.0  # a held call goes on by itself after this, so a forgotten release cannot hang a test

# (method, params) -> hold this call?
CallFilter = Callable[[str, Tuple], bool]


class _QuietHandler(SimpleXMLRPCRequestHandler):
    def log_message(self, *_args) -> None:
        pass


class _ThreadingServer(ThreadingMixIn, SimpleXMLRPCServer):
    daemon_threads = True


class MasterRelay:
    """Forwards XML-RPC calls from nodes to the master at `upstream`; the first call matching
    `hold` waits until release(). `held` is set once that call has arrived."""

    def __init__(self, upstream: str, hold: CallFilter) -> None:
        self.upstream = upstream
        self._hold = hold
        self.held = threading.Event()
        self.held_call: Optional[Tuple[str, Tuple]] = None
        self._released = threading.Event()
        self._server = _ThreadingServer(("127.0.0.1", 0), requestHandler=_QuietHandler, logRequests=False,
                                        allow_none=True)
        self._server.register_instance(self, allow_dotted_names=False)
        self.uri = "http://127.0.0.1:%d/" % self._server.server_address[1]
        self._thread = threading.Thread(target=self._server.serve_forever, name="master_relay", daemon=True)

    def _dispatch(self, method: str, params: Tuple):
        if not self.held.is_set() and self._hold(method, params):
            self.held_call = (method, params)
            self.held.set()
            self._released.wait(HOLD_TIMEOUT_S)
        return getattr(xmlrpc.client.ServerProxy(self.upstream), method)(*params)

    def release(self) -> None:
        """Let the held call (and any later one) through."""
        self._released.set()

    def __enter__(self) -> "MasterRelay":
        self._thread.start()
        return self

    def __exit__(self, exc_type: Optional[Type[BaseException]], exc: Optional[BaseException],
                 tb: Optional[TracebackType]) -> None:
        self.release()
        self._server.shutdown()
        self._server.server_close()
