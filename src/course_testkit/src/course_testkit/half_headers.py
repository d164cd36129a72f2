"""Half-sent TCPROS headers against a running node, and what they cost it, read from /proc: the
scenarios of issue 40 (course_rospy.inbound_headers) on the three nodes that install it, which
their tests assert on (test_half_headers.py of turtlesim, mujoco_gazebo and course_relay) and
bench/idle_connection_bench.py prints.

A half header is 2 of the 4 bytes of a handshake header's length, the least a client can send
that is neither nothing (the idle, slowloris case) nor a length.
"""
from __future__ import annotations

import os
import socket
import time
from dataclasses import dataclass
from typing import Callable, List, Tuple

from course_checks.waiting import wait_for
from course_sandbox import procs

HALF_HEADER = b"\x20\x00"
# "Within 1 s" of the issue: how long a node may take to give back what half headers cost, and
# to serve a well-behaved subscriber or caller beside 500 of them.
DEADLINE_S = 1.0
# How long CPU use is measured, quiet and beside the open half headers.
CPU_WINDOW_S = 1.0


@dataclass(frozen=True)
class ProcessUse:
    """A process's threads, open files and CPU time so far (user + system)."""
    threads: int
    files: int
    cpu_s: float

    def __str__(self) -> str:
        return "%d threads, %d open files" % (self.threads, self.files)


def process_use(pid: int) -> ProcessUse:
    use = procs.usage(pid)
    if use is None:
        raise ProcessLookupError(pid)
    return ProcessUse(threads=use.tasks, files=len(os.listdir("/proc/%d/fd" % pid)), cpu_s=use.cpu_seconds)


def cpu_share(pid: int, seconds: float = CPU_WINDOW_S) -> float:
    """CPU seconds per second `pid` used over the next `seconds` (this measures, so it waits)."""
    before, started = process_use(pid).cpu_s, time.monotonic()
    time.sleep(seconds)
    return (process_use(pid).cpu_s - before) / (time.monotonic() - started)


def open_half_headers(address: Tuple[str, int], count: int, timeout: float = 5.0) -> List[socket.socket]:
    """`count` connections to `address`, each having sent HALF_HEADER (the caller closes them)."""
    socks: List[socket.socket] = []
    try:
        for _ in range(count):
            sock = socket.create_connection(address, timeout=timeout)
            socks.append(sock)
            sock.sendall(HALF_HEADER)
    except BaseException:
        close_all(socks)
        raise
    return socks


def close_all(socks: List[socket.socket]) -> None:
    for sock in socks:
        sock.close()


def settled_use(pid: int, timeout: float = 5.0) -> ProcessUse:
    """The process's use once its thread and file counts read the same twice 0.1 s apart (a
    baseline after the handshake threads of a warm-up have ended)."""
    last = [process_use(pid)]

    def steady():
        time.sleep(0.1)
        now = process_use(pid)
        same = (now.threads, now.files) == (last[0].threads, last[0].files)
        last[0] = now
        return same and now
    return wait_for(steady, timeout, interval=0) or last[0]


def back_within(pid: int, baseline: ProcessUse, deadline: float = DEADLINE_S) -> ProcessUse:
    """The process's use as soon as its threads and files are back to `baseline` or fewer, or
    at `deadline` s if not."""
    last = [process_use(pid)]

    def back():
        last[0] = process_use(pid)
        return last[0].threads <= baseline.threads and last[0].files <= baseline.files
    wait_for(back, deadline, interval=0.01)
    return last[0]


def served_within(action: Callable[[float], object], deadline: float = DEADLINE_S) -> float:
    """Seconds `action(timeout)` (a subscriber's first message, a service call) took; raises
    what it raised (socket.timeout past `deadline`)."""
    started = time.monotonic()
    action(deadline)
    return time.monotonic() - started


@dataclass
class NodeUnderTest:
    """A running node: its pid, its TCPROS address, and a well-behaved subscriber's first message
    and service call, each `action(timeout)`."""
    pid: int
    address: Tuple[str, int]
    subscribe: Callable[[float], object]
    call: Callable[[float], object]

    def warmed_up(self) -> ProcessUse:
        """Its use once it has served one subscriber and one call (threads and connections that
        rospy makes on first use exist, handshake threads have ended)."""
        self.subscribe(5.0)
        self.call(5.0)
        return settled_use(self.pid)


# Beside any number of open half headers, a node's threads and files stay within its baseline and
# these (course_rospy.inbound_headers: one thread, MAX_WAITING_HEADERS sockets; the margins are a
# handshake thread and its socket, for a well-behaved client the test's own checks bring).
THREAD_MARGIN = 2


def check_half_headers_that_close(node: NodeUnderTest, count: int = 50) -> None:
    """`count` half headers that close: threads and files back to the baseline within 1 s."""
    baseline = node.warmed_up()
    close_all(open_half_headers(node.address, count))
    after = back_within(node.pid, baseline)
    assert after.threads <= baseline.threads and after.files <= baseline.files, (
        "%d half headers that closed, %.0f s later: %s, against %s before" % (count, DEADLINE_S, after, baseline))


def check_half_headers_left_open(node: NodeUnderTest, max_waiting: int, count: int = 500,
                                 cpu_margin: float = 0.1) -> None:
    """`count` half headers left open: threads within baseline + THREAD_MARGIN, files within
    baseline + `max_waiting` + 1 (as soon as the last is in), CPU at most `cpu_margin` s/s
    over the quiet node's, a subscriber's first message and a service call within 1 s each."""
    baseline = node.warmed_up()
    quiet_cpu = cpu_share(node.pid)
    socks = open_half_headers(node.address, count)
    try:
        bound = ProcessUse(baseline.threads + THREAD_MARGIN, baseline.files + max_waiting + 1, 0.0)
        within = back_within(node.pid, bound)
        assert within.threads <= bound.threads and within.files <= bound.files, (
            "%d open half headers: %s, against %s before (bound %s)" % (count, within, baseline, bound))
        busy_cpu = cpu_share(node.pid)
        assert busy_cpu <= quiet_cpu + cpu_margin, (
            "%d open half headers: %.2f CPU s/s, against %.2f quiet" % (count, busy_cpu, quiet_cpu))
        served_within(node.subscribe)
        served_within(node.call)
        assert process_use(node.pid).files <= bound.files + 1
    finally:
        close_all(socks)


def check_idle_connection(node: NodeUnderTest) -> None:
    """One connection that sends nothing (slowloris): a subscriber and a caller still served
    within 1 s each."""
    with socket.create_connection(node.address, timeout=DEADLINE_S):
        served_within(node.subscribe)
        served_within(node.call)

