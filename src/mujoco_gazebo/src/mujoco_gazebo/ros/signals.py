"""Ctrl+C (SIGINT) and SIGTERM for a node whose main thread talks to rospy before it waits.

Python runs a signal handler on the main thread, between two of its bytecodes, wherever that
thread is. rospy's own handler runs rospy's whole shutdown there: it unregisters from the
master and closes connections. If the main thread was inside a call to the master (registering
a service) or a queued publish (a log line to /rosout), the shutdown waits for the lock that
interrupted call holds, and the node hangs for ever. So the node starts rospy with
disable_signals=True and installs these handlers instead: they only note the signal, and the
main thread shuts rospy down itself once it is waiting, holding no lock."""
from __future__ import annotations

import signal
import time
from typing import Optional

import rospy

SIGNALS = (signal.SIGINT, signal.SIGTERM)
POLL_S = 0.1  # how soon a noted signal becomes rospy's shutdown


class DeferredShutdown:
    """install() before rospy.init_node(..., disable_signals=True); wait() when the node is up."""

    def __init__(self) -> None:
        self.signal: Optional[int] = None

    def install(self) -> "DeferredShutdown":
        for sig in SIGNALS:
            signal.signal(sig, self._note)
        return self

    def _note(self, signum: int, _frame) -> None:
        if self.signal is None:
            self.signal = signum

    def wait(self) -> None:
        """Until a signal came (then shut rospy down, with rospy's reason for it) or rospy shut
        down for another reason (the master asked, the node gave up)."""
        while self.signal is None and not rospy.is_shutdown():
            time.sleep(POLL_S)
        if self.signal is not None:
            rospy.signal_shutdown("signal-%d" % self.signal)
