"""Where a run's pids cgroup goes, read from /proc/self/mountinfo and /proc/self/cgroup texts."""
from course_sandbox import pids_cgroup
from course_sandbox.pids_cgroup import PidsCgroup, parent_from

V1_MOUNTS = """\
31 23 0:28 / /sys/fs/cgroup rw,relatime - tmpfs tmpfs rw,mode=755
32 31 0:29 / /sys/fs/cgroup/cpu rw,relatime - cgroup cgroup rw,cpu
39 31 0:36 / /sys/fs/cgroup/pids rw,relatime - cgroup cgroup rw,pids
41 31 0:38 / /sys/fs/cgroup/unified rw,relatime - cgroup2 cgroup2 rw
"""
V1_OWN = "8:pids:/grading/job1\n1:cpu:/\n0::/\n"
V2_MOUNTS = "35 24 0:30 / /sys/fs/cgroup rw,nosuid,nodev,noexec,relatime shared:9 - cgroup2 cgroup2 rw,nsdelegate\n"


def test_cgroup_v1_pids_hierarchy_is_preferred():
    assert parent_from(V1_MOUNTS, V1_OWN) == "/sys/fs/cgroup/pids/grading/job1"
    assert parent_from(V1_MOUNTS, "8:pids:/\n0::/\n") == "/sys/fs/cgroup/pids"


def test_cgroup_v2_is_used_where_no_v1_pids_hierarchy_is_mounted():
    assert parent_from(V2_MOUNTS, "0::/user.slice/session-3.scope\n") == "/sys/fs/cgroup/user.slice/session-3.scope"
    assert parent_from(V2_MOUNTS, "0::/\n") == "/sys/fs/cgroup"


def test_a_mount_of_part_of_the_hierarchy_shows_only_what_is_below_its_root():
    """A container's /sys/fs/cgroup may be a bind of one cgroup: a path outside it is not reachable."""
    mounts = "35 24 0:30 /docker/abc /sys/fs/cgroup rw - cgroup2 cgroup2 rw\n"
    assert parent_from(mounts, "0::/docker/abc/sub\n") == "/sys/fs/cgroup/sub"
    assert parent_from(mounts, "0::/docker/abc\n") == "/sys/fs/cgroup"
    assert parent_from(mounts, "0::/other\n") is None


def test_no_cgroup_mount_or_malformed_lines_give_none():
    assert parent_from("", V1_OWN) is None
    assert parent_from("garbage\n1 2 3\n - \n", "x\n") is None
    assert parent_from(V1_MOUNTS.replace("rw,pids", "rw,memory"), V1_OWN) == "/sys/fs/cgroup/unified"


def test_the_counts_of_a_cgroup_folder(tmp_path):
    (tmp_path / "pids.current").write_text("17\n")
    (tmp_path / "pids.events").write_text("max 4\n")
    (tmp_path / "cgroup.procs").write_text("12\n34\n")
    group = PidsCgroup(str(tmp_path))
    assert (group.tasks(), group.refusals(), group.members()) == (17, 4, [12, 34])
    assert group.join_prefix()[-1] == str(tmp_path / "cgroup.procs")
    gone = PidsCgroup(str(tmp_path / "gone"))
    assert (gone.tasks(), gone.refusals(), gone.members()) == (0, 0, [])
    assert gone.remove(), "a cgroup already gone counts as removed"


def test_the_sentence_says_which_counts_the_processes():
    assert "pids cgroup" in pids_cgroup.describe(True, 1024)
    assert "RLIMIT_NPROC" in pids_cgroup.describe(False, 1024)
