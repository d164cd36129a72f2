"""What the benchmarks (bench/) share: a private master set up for them, a process's CPU time and
anonymous memory, and the reference's exercise packages as a student hands them in."""
from __future__ import annotations

import os
from contextlib import contextmanager
from typing import Iterator, List

from course_format import course_file
from course_testkit.master import PrivateMaster


def cpu_seconds(pid: int) -> float:
    """utime + stime of a process, in seconds."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def rss_anon_kib(pid: int) -> int:
    """A process's anonymous resident memory (RssAnon), in KiB: what it costs beyond shared files."""
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("RssAnon:"):
                return int(line.split()[1])
    return 0


@contextmanager
def private_master(rosout: bool = True) -> Iterator[PrivateMaster]:
    """course_testkit's private master (by default with rosout, as `roscore` gives), pointed to by
    this process (rospy) and by every node it starts, headless; all of it stopped after the block."""
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
    master = PrivateMaster(rosout=rosout)
    master.export()
    with master:
        yield master


def student_packages() -> List[str]:
    """The packages the built-in course's milestones grade: the reference's, as one student hands them in."""
    milestones = course_file.load(course_file.builtin_course_dir()).milestones
    return sorted({p for m in milestones for p in m.packages})
