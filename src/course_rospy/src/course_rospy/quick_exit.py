"""A rospy node's exit without a core spinning: rospy's XML-RPC server stopped before its socket closes.

At shutdown rospy closes its XML-RPC server's socket while the server's thread waits in
`select()` inside `serve_forever()`, whose loop is never told to stop. The loop goes on with a
closed descriptor: it blocks in `accept()`, or, when the descriptor's number has been reused by
then (rospy closes its topic connections at the same moment), `select()` returns at once, `accept()`
fails and the loop goes round again: the thread spins on a core from rospy's shutdown until the
process exits (rospy's shutdown alone waits 0.6 s for its threads). turtlesim spent 0.54 of its
0.58 CPU s of a short run that way. A milestone run ends several nodes, so this was a large share of a grading's CPU
(docs/benchmarks.md, "Where a grading's time goes").

A second wait: rospy's shutdown joins its registration thread (RegManager), which polls its
queue every 0.5 s until rospy is shut down. The thread is woken once, by a pre-shutdown hook,
before rospy raises its shut-down flag: it goes round, finds rospy still running and waits its
0.5 s again, while `signal_shutdown` waits for it. Every rospy node's exit took 0.5 s longer:
turtlesim's 0.84 s after SIGINT, a check's 0.6 s after its last test (several per milestone run).

`install()` wraps `rosgraph.xmlrpc.XmlRpcNode.shutdown` (a shutdown hook: it runs once the flag
is up) so that the loop is asked to stop (socketserver's own `shutdown()`, on a helper thread
since it waits for the loop) and the node marked shut down before the socket closes; the loop
then ends at its next turn; and the registration thread is woken again, now to find rospy shut
down and end. Call it before `rospy.init_node`, which binds the method it calls at shutdown.

A third: `rospy.spin()` looks at the flag every 0.5 s. `spin()` here returns as soon as rospy is
shut down (SIGINT included: rospy's handler runs while the main thread waits).
"""
from __future__ import annotations

import os
import select
import signal
import threading

import rosgraph.xmlrpc

_original_shutdown = rosgraph.xmlrpc.XmlRpcNode.shutdown


def wake_registration(handler: object) -> None:
    """Wake the registration thread of rospy's node `handler` (a ROSHandler), if it has one, so
    that it sees the shut-down flag now rather than after its 0.5 s poll."""
    cond = getattr(getattr(handler, "reg_man", None), "cond", None)
    if cond is not None:
        with cond:
            cond.notify_all()


def _shutdown(self: rosgraph.xmlrpc.XmlRpcNode, reason: str) -> None:
    server = self.server
    wake_registration(self.handler)
    self.is_shutdown = True  # XmlRpcNode._run's loop calls serve_forever() again unless it is set
    if server is not None:
        stopper = threading.Thread(target=server.shutdown, name="xmlrpc-stop", daemon=True)
        stopper.start()
        stopper.join(0.01)  # serve_forever() notices at its next turn; the flag is set by now
    _original_shutdown(self, reason)


def spin() -> None:
    """rospy.spin() without its 0.5 s poll: block until rospy is shut down. Call it from the main
    thread. A signal may reach any of the process's threads, while Python runs its handler
    (rospy's, for SIGINT) only in the main thread once that thread runs: the signal's wake-up
    byte (signal.set_wakeup_fd) and rospy's shutdown both write to a pipe this thread waits on."""
    import rospy  # here, not at the top: turtlesim.startup decides when rospy is first imported

    reader, writer = os.pipe()  # left open: a shutdown hook may still write after spin() returns
    os.set_blocking(writer, False)

    def wake() -> None:
        try:
            os.write(writer, b"\0")
        except OSError:  # full: a wake-up is pending anyway
            pass
    previous = signal.set_wakeup_fd(writer)
    try:
        rospy.on_shutdown(wake)  # called at once when rospy is already shut down
        while not rospy.is_shutdown():
            select.select([reader], [], [])
            os.read(reader, 512)  # back in Python: a signal's handler runs here
    finally:
        signal.set_wakeup_fd(previous)


def install() -> None:
    """From now on, every XmlRpcNode of this process (rospy's node server) stops its loop at shutdown."""
    rosgraph.xmlrpc.XmlRpcNode.shutdown = _shutdown
