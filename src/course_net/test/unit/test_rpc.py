"""TimedTransport: a server that accepts the connection and never answers stalls the call only for
the time limit, and a server that answers is asked as usual."""
import socket
import threading
import time
import xmlrpc.client
import xmlrpc.server

import pytest

from course_net.rpc import TimedTransport


def test_a_silent_server_is_given_up_after_the_limit():
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(1)  # the kernel accepts; nobody ever reads or answers
        proxy = xmlrpc.client.ServerProxy("http://127.0.0.1:%d" % silent.getsockname()[1],
                                          transport=TimedTransport(0.3))
        began = time.monotonic()
        with pytest.raises(OSError):
            proxy.getPid("/caller")
        assert time.monotonic() - began < 5.0


def test_an_answering_server_is_asked_as_usual():
    server = xmlrpc.server.SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False)
    server.register_function(lambda caller: [1, "", 42], "getPid")
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        proxy = xmlrpc.client.ServerProxy("http://127.0.0.1:%d" % server.server_address[1],
                                          transport=TimedTransport(5.0))
        assert proxy.getPid("/caller") == [1, "", 42]
    finally:
        server.shutdown()
        server.server_close()
