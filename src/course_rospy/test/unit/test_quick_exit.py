"""quick_exit: after shutdown, rospy's XML-RPC server thread ends instead of spinning.
A real rosgraph XmlRpcNode (the server every rospy node runs); no master needed."""
import threading
import time

import pytest
import rosgraph.xmlrpc

from course_rospy import quick_exit


class Handler(rosgraph.xmlrpc.XmlRpcHandler):
    def _ready(self, uri):
        pass

    def _shutdown(self, reason):
        pass


def serving_node():
    node = rosgraph.xmlrpc.XmlRpcNode(0, Handler())
    thread = threading.Thread(target=node.run, daemon=True)  # what node.start() runs, with a handle
    thread.start()
    deadline = time.monotonic() + 10
    while not node.uri and time.monotonic() < deadline:
        time.sleep(0.01)
    assert node.uri, "the XML-RPC server did not start"
    return node, thread


def thread_cpu_after_shutdown(node, thread, window=0.3):
    """CPU seconds this process spends in the `window` after node.shutdown, and whether the server thread ended."""
    node.shutdown("test")
    start = time.thread_time(), time.process_time()
    time.sleep(window)
    spent = time.process_time() - start[1] - (time.thread_time() - start[0])
    thread.join(1.0)
    return spent, not thread.is_alive()


@pytest.fixture
def original():
    yield
    rosgraph.xmlrpc.XmlRpcNode.shutdown = quick_exit._original_shutdown


def test_without_it_the_server_thread_outlives_shutdown(original):
    """Blocked in accept() on the closed socket, or spinning when its descriptor number was reused
    by then (as in turtlesim: 0.5 CPU s at exit); either way it never ends."""
    node, thread = serving_node()
    _, ended = thread_cpu_after_shutdown(node, thread)
    assert not ended, "rosgraph's server now ends at shutdown: quick_exit may go"


def test_with_it_the_server_thread_ends_and_nothing_spins(original):
    quick_exit.install()
    node, thread = serving_node()
    spent, ended = thread_cpu_after_shutdown(node, thread)
    assert ended, "the XML-RPC server thread still runs after shutdown"
    assert spent < 0.05, "%.3f CPU s spent after shutdown" % spent
