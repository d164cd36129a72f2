"""The sweep that ends a grading's leftovers where no PID namespace holds them (isolation `user
only`): it ends that grading's processes, and not those of another grading run by the same user."""
import os
import pwd
import subprocess

import pytest

from course_sandbox import procs
from course_sandbox.policy import DEFAULT_USER, grading_gid
from course_sandbox.run import end_user_processes
from course_checks.waiting import wait_for

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="switching to the sandbox user needs root")


def _user_exists() -> bool:
    try:
        pwd.getpwnam(DEFAULT_USER)
        return True
    except KeyError:
        return False


@pytest.mark.skipif(not _user_exists(), reason="setup/install.sh creates the sandbox user")
def test_the_sweep_ends_one_gradings_processes_only():
    mine, theirs = grading_gid(os.getpid()), grading_gid(os.getpid() + 1)

    def leftover(gid):
        # A helper that left its session and emptied its environment, as the sandbox user.
        return subprocess.Popen(["setpriv", "--reuid", DEFAULT_USER, "--regid", str(gid), "--clear-groups",
                                 "--", "env", "-i", "setsid", "sleep", "60"])
    ours, other = leftover(mine), leftover(theirs)
    uid = pwd.getpwnam(DEFAULT_USER).pw_uid
    try:
        for proc, gid in ((ours, mine), (other, theirs)):
            assert wait_for(lambda: (procs.owner(proc.pid), procs.real_group(proc.pid)) == (uid, gid), 10), \
                "setpriv switched to the sandbox user and the grading's group"
        assert end_user_processes(DEFAULT_USER, mine) >= 1
        assert ours.wait(10) == -9
        assert other.poll() is None, "another grading's process must survive this grading's sweep"
    finally:
        for proc in (ours, other):
            proc.kill()
            proc.wait()
