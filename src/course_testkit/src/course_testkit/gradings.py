"""For tests of gradings: what a grading left running, and stand-ins for a grading's processes
(course_sandbox.leftovers, the grader's claim on its output folder)."""
from __future__ import annotations

import contextlib
import os
import subprocess
import sys
from pathlib import Path
from typing import Iterator, List

from course_sandbox import leftovers
from course_checks.waiting import wait_for

# sh marks itself with its own pid, then execs Python in its place (the same pid, the mark in the
# environment it was exec'd with, which is what /proc/<pid>/environ shows).
_MARK_AND_SLEEP = 'export %s=$$; exec "$0" -c "import time; time.sleep(120)"' % leftovers.GRADER_VAR


@contextlib.contextmanager
def live_grader() -> Iterator[subprocess.Popen]:
    """A process that is a live grading until the block ends (then it is killed)."""
    proc = subprocess.Popen(["sh", "-c", _MARK_AND_SLEEP, sys.executable])
    try:
        assert wait_for(lambda: leftovers.is_live_grader(proc.pid), 10.0), "the stand-in grader did not start"
        yield proc
    finally:
        proc.kill()
        proc.wait()


def gone_pid() -> int:
    """The pid of a process that has exited (until the kernel hands the number out again)."""
    proc = subprocess.Popen(["true"])
    proc.wait()
    return proc.pid


def processes_of(out: str) -> List[str]:
    """The processes of the grading into the output folder `out` ("<pid> <command line>"): every
    run's trusted processes carry COURSE_ARTIFACTS_DIR under it, and every sandboxed student
    process has its workspace mounted from there, whatever it did to its environment."""
    marker = str(out).encode()
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            environ = Path("/proc", pid, "environ").read_bytes()
            mounts = Path("/proc", pid, "mountinfo").read_bytes()
            cmdline = Path("/proc", pid, "cmdline").read_bytes().replace(b"\0", b" ")
        except OSError:
            continue
        if (marker in environ or marker in mounts) and int(pid) != os.getpid():
            found.append("%s %s" % (pid, cmdline.decode(errors="replace")))
    return found
