"""leftovers: a grading is live only while its grader carries its own mark; a pids cgroup is
stale once the process that made it is gone; a dead grading's processes are found by mark and
by group, and a live one's never."""
import os
import subprocess
import sys

from course_sandbox import leftovers
from course_sandbox.policy import grading_gid
from course_sandbox.pids_cgroup import NAME_PREFIX
from course_testkit.gradings import gone_pid as dead_pid, live_grader
from course_checks.waiting import wait_for


def sleeper(env):
    return subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"], env=env)


def test_a_process_marked_by_a_gone_grader_is_found_and_one_of_a_live_grader_is_not():
    gone = dead_pid()
    orphan = sleeper(dict(os.environ, **{leftovers.GRADER_VAR: str(gone)}))
    with live_grader() as grader:
        assert leftovers.is_live_grader(grader.pid)
        assert not leftovers.is_live_grader(gone)
        child = sleeper(dict(os.environ, **{leftovers.GRADER_VAR: str(grader.pid)}))
        try:
            seen = wait_for(lambda: orphan.pid in leftovers.dead_gradings_processes()
                            and leftovers.grading_of(child.pid) == grader.pid, 10.0)
            found = leftovers.dead_gradings_processes()
        finally:
            child.kill()
            child.wait()
    if not seen:
        orphan.kill()
    assert seen, "the orphan of a gone grading was not found"
    assert child.pid not in found and grader.pid not in found
    assert leftovers.end_all(lambda: [orphan.pid] if orphan.poll() is None else []) == 1
    assert orphan.wait(5) == -9


def test_a_grading_group_names_its_grader():
    assert leftovers._grading_gid_owner(grading_gid(4242)) == 4242
    assert leftovers._grading_gid_owner(1000) is None
    assert leftovers._grading_gid_owner(None) is None


def test_stale_cgroups_are_those_whose_maker_is_gone(tmp_path):
    gone = dead_pid()
    for name in ("%s%d-0" % (NAME_PREFIX, gone), "%s%d-3" % (NAME_PREFIX, os.getpid()), "other-%d-0" % gone):
        (tmp_path / name).mkdir()
    assert [os.path.basename(g.path) for g in leftovers.stale_cgroups(str(tmp_path))] == ["%s%d-0" % (NAME_PREFIX, gone)]
    assert leftovers.stale_cgroups(None) == []


def test_an_environment_marked_here_marks_this_process_only():
    assert leftovers.is_marked(leftovers.marked({"A": "1"}))
    assert not leftovers.is_marked({leftovers.GRADER_VAR: str(dead_pid())})
    assert not leftovers.is_marked({})
