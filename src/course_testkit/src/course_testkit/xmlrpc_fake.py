"""A stand-in for a node's or a master's XML-RPC API in a unit test: Python's own server on
loopback, answering only the functions given, on a thread of its own, stopped after the block."""
from __future__ import annotations

import threading
import xmlrpc.server
from contextlib import contextmanager
from typing import Callable, Iterator, Mapping

# How often the server's loop looks for shutdown(): the block's end waits at most this long.
POLL_S = 0.01


@contextmanager
def serving(functions: Mapping[str, Callable]) -> Iterator[str]:
    """A server whose methods are `functions` (name -> function, called with the request's
    arguments; None may be answered); yields its URI."""
    server = xmlrpc.server.SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
    for name, function in functions.items():
        server.register_function(function, name)
    threading.Thread(target=server.serve_forever, args=(POLL_S,), daemon=True).start()
    try:
        yield "http://127.0.0.1:%d/" % server.server_address[1]
    finally:
        server.shutdown()
        server.server_close()
