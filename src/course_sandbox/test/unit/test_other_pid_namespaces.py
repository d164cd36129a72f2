"""A grading's sweeps judge the processes of their own PID namespace only. A grading in a container
(the course image's `make grade` or `make test`, a hub student's course-check) marks its processes
with its pid in the container's namespace, which names another process, or none, on the machine:
a sweep there took it for a dead grading and killed it (docker-check's `make grade` in the
instructor image: `make: *** [Makefile: grade] Killed` while the machine graded too)."""
import os
import shutil
import subprocess
import time

import pytest

from course_sandbox import leftovers, procs

OWN = "pid:[4026531836]"
CONTAINER = "pid:[4026532999]"


def test_local_pids_are_this_namespaces_own():
    local = procs.local_pids()
    assert os.getpid() in local and os.getppid() in local
    assert {procs.pid_namespace(pid) for pid in local} <= {procs.pid_namespace(os.getpid())}


def test_a_grading_in_a_container_is_not_a_dead_one_here(monkeypatch):
    # 101 (this namespace) and 202 (a container's) are both marked with grader 7, which is no
    # grading here: 101 is a dead grading's leftover, 202 a live grading's process in its container.
    me = os.getpid()
    namespaces = {me: OWN, 101: OWN, 202: CONTAINER}
    monkeypatch.setattr(procs, "pids", lambda: iter([me, 101, 202, 7]))
    monkeypatch.setattr(procs, "pid_namespace", lambda pid: namespaces.get(pid, OWN))
    monkeypatch.setattr(procs, "environ", lambda pid: [b"COURSE_GRADER_PID=7"] if pid in (101, 202) else [])
    monkeypatch.setattr(procs, "real_group", lambda pid: None)
    assert leftovers.dead_gradings_processes() == [101]


def _unshare_pid() -> list:
    """A command prefix that starts a process in a PID namespace of its own, or [] where this
    machine refuses one (no root and no user namespaces: the course image)."""
    if not shutil.which("unshare"):
        return []
    prefix = ["unshare", "--pid", "--fork", "--kill-child"] if os.geteuid() == 0 else \
        ["unshare", "--user", "--map-root-user", "--pid", "--fork", "--kill-child"]
    done = subprocess.run(prefix + ["true"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    return prefix if done.returncode == 0 else []


def test_a_live_grading_in_its_own_pid_namespace_is_left_alone():
    prefix = _unshare_pid()
    if not prefix:
        pytest.skip("this machine gives no PID namespace of its own (no root, no user namespaces)")
    # pid 1 of its namespace, marked with its own pid there: a live grading, as in a container
    grading = subprocess.Popen(prefix + ["env", "%s=1" % leftovers.GRADER_VAR, "sleep", "60"])
    try:
        deadline = time.monotonic() + 10
        inner = None
        while inner is None and time.monotonic() < deadline:
            inner = next((pid for pid in procs.descendants(grading.pid) if procs.namespace_pid(pid) == 1
                          and leftovers.grading_of(pid) == 1), None)
            time.sleep(0.05)
        assert inner is not None, "the marked process in its own namespace did not start"
        assert inner not in procs.local_pids()
        assert inner not in leftovers.dead_gradings_processes()
    finally:
        grading.kill()
        grading.wait()
