"""A private ROS master for benchmarks: free loopback port, own ROS_HOME, everything stopped after."""
from __future__ import annotations

import os
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, List

from course_testkit.isolation import free_port


def cpu_seconds(pid: int) -> float:
    """utime + stime of a process, in seconds."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


class Processes:
    """Nodes started in their own process groups (course_testkit's NodeProcess), stopped together."""

    def __init__(self, scratch: Path) -> None:
        self.scratch = scratch
        self.procs: List = []

    def start(self, argv: List[str], name: str):
        from course_testkit.nodes import NodeProcess
        proc = NodeProcess(argv, log_path=str(self.scratch / ("%s.log" % name)))
        self.procs.append(proc)
        return proc

    def stop_all(self) -> None:
        for proc in reversed(self.procs):
            proc.stop()
        self.procs.clear()


@contextmanager
def private_master() -> Iterator[Processes]:
    """Set ROS_MASTER_URI to a fresh roscore on loopback for the duration of the block."""
    scratch = Path(tempfile.mkdtemp(prefix="bench-"))
    port = free_port()
    os.environ.update(ROS_MASTER_URI="http://localhost:%d" % port, ROS_HOSTNAME="localhost",
                      ROS_HOME=str(scratch), ROS_LOG_DIR=str(scratch / "log"), QT_QPA_PLATFORM="offscreen")
    procs = Processes(scratch)
    try:
        procs.start(["roscore", "-p", str(port)], "roscore")
        import rosgraph
        deadline = time.monotonic() + 30
        while not rosgraph.Master("/bench").is_online():
            if time.monotonic() > deadline:
                raise RuntimeError("roscore did not start")
            time.sleep(0.1)
        yield procs
    finally:
        procs.stop_all()
