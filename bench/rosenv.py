"""What the benchmarks share: a private master set up for them, and a process's CPU time."""
from __future__ import annotations

import os
from contextlib import contextmanager
from typing import Iterator

from course_testkit.master import PrivateMaster


def cpu_seconds(pid: int) -> float:
    """utime + stime of a process, in seconds."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@contextmanager
def private_master(rosout: bool = True) -> Iterator[PrivateMaster]:
    """course_testkit's private master (by default with rosout, as `roscore` gives), pointed to by
    this process (rospy) and by every node it starts, headless; all of it stopped after the block."""
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
    master = PrivateMaster(rosout=rosout)
    master.export()
    with master:
        yield master
