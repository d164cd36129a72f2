"""course_sandbox.procs.cpu_with_ended_children: a child's CPU counts once it is waited for."""
import os
import subprocess
import sys

from course_sandbox import procs

BURN = "import time\nend = time.process_time() + 0.3\nwhile time.process_time() < end: pass"


def test_cpu_with_ended_children_counts_a_child_once_it_is_waited_for():
    before = procs.cpu_with_ended_children(os.getpid())
    subprocess.run([sys.executable, "-c", BURN], check=True)
    after = procs.cpu_with_ended_children(os.getpid())
    assert after - before >= 0.25, (before, after)  # the child's 0.3 s, now the parent's to count


def test_no_such_process_has_none():
    assert procs.cpu_with_ended_children(2 ** 22 + 1) is None
