"""A rospy node's exit without a core spinning: rospy's XML-RPC server stopped before its socket closes.

At shutdown rospy closes its XML-RPC server's socket while the server's thread waits in
`select()` inside `serve_forever()`, whose loop is never told to stop. The loop goes on with a
closed descriptor: it blocks in `accept()`, or, when the descriptor's number has been reused by
then (rospy closes its topic connections at the same moment), `select()` returns at once, `accept()`
fails and the loop goes round again: the thread spins on a core from rospy's shutdown until the
process exits (rospy's shutdown alone waits 0.6 s for its threads). turtlesim spent 0.54 of its
0.58 CPU s of a short run that way. A milestone run ends several nodes, so this was a large share of a grading's CPU
(docs/benchmarks.md, "Where a grading's time goes").

`install()` wraps `rosgraph.xmlrpc.XmlRpcNode.shutdown` so that the loop is asked to stop
(socketserver's own `shutdown()`, on a helper thread since it waits for the loop) and the node
marked shut down before the socket closes; the loop then ends at its next turn. Call it before
`rospy.init_node`, which binds the method it calls at shutdown.
"""
from __future__ import annotations

import threading

import rosgraph.xmlrpc

_original_shutdown = rosgraph.xmlrpc.XmlRpcNode.shutdown


def _shutdown(self: rosgraph.xmlrpc.XmlRpcNode, reason: str) -> None:
    server = self.server
    self.is_shutdown = True  # XmlRpcNode._run's loop calls serve_forever() again unless it is set
    if server is not None:
        stopper = threading.Thread(target=server.shutdown, name="xmlrpc-stop", daemon=True)
        stopper.start()
        stopper.join(0.01)  # serve_forever() notices at its next turn; the flag is set by now
    _original_shutdown(self, reason)


def install() -> None:
    """From now on, every XmlRpcNode of this process (rospy's node server) stops its loop at shutdown."""
    rosgraph.xmlrpc.XmlRpcNode.shutdown = _shutdown
