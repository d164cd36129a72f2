"""A student's disk: a file system of a fixed size, loop-mounted, that the kernel bounds (root
and loop devices needed, as on the hub's machine); the data folder's modes against the grader's
sandbox user."""
from __future__ import annotations

import errno
import os
import pwd
import shutil
import subprocess
import tempfile

import pytest

from course_hub import disks, grading, layout, names

ROOT = os.geteuid() == 0
LOOP = os.path.exists("/dev/loop-control") and shutil.which("mkfs.ext4", path="/usr/sbin:/sbin:/usr/bin") is not None


def test_sizes_are_read_as_people_write_them():
    assert disks.size_bytes("1G") == 2 ** 30 and disks.size_bytes("512M") == 512 * 2 ** 20
    assert disks.size_bytes("16MiB") == 16 * 2 ** 20 and disks.size_bytes("9000000") == 9000000
    for bad in ("", "lots", "1X", "1M", "-5G"):
        with pytest.raises(ValueError):
            disks.size_bytes(bad)


@pytest.fixture
def place(tmp_path):
    place = names.places(str(tmp_path / "data"), "jean_luc")
    yield place
    disks.unmount(place)


@pytest.mark.skipif(not (ROOT and LOOP), reason="loop-mounting needs root and loop devices")
def test_a_student_who_fills_their_disk_gets_no_space_and_nothing_else_notices(place, tmp_path):
    disks.ensure(place, 16 * 2 ** 20, uid=1000)
    assert os.path.ismount(place.home) and os.stat(place.src).st_uid == 1000
    assert os.stat(place.disk_image).st_blocks * 512 >= 16 * 2 ** 20  # reserved up front: cannot grow the host's use
    free_before = shutil.disk_usage(tmp_path).free
    with pytest.raises(OSError) as err:
        with open(os.path.join(place.src, "fill"), "wb") as out:
            for _ in range(64):
                out.write(b"\0" * 2 ** 20)
                out.flush()
                os.fsync(out.fileno())
    assert err.value.errno == errno.ENOSPC
    assert free_before - shutil.disk_usage(tmp_path).free < 8 * 2 ** 20  # the host's disk: untouched
    with open(os.path.join(place.src, "kept"), "w") as out:  # (made room: her files are hers to remove)
        os.remove(os.path.join(place.src, "fill"))
        out.write("mine")
    disks.ensure(place, 16 * 2 ** 20, uid=1000)  # the next spawn: the same disk, her files on it
    assert open(os.path.join(place.src, "kept")).read() == "mine"
    disks.unmount(place)
    assert not os.path.exists(os.path.join(place.src, "kept"))
    assert grading.user_src(os.path.dirname(os.path.dirname(place.home)), place.user) == place.src  # mounted again
    assert open(os.path.join(place.src, "kept")).read() == "mine"


@pytest.mark.skipif(not (ROOT and LOOP), reason="loop-mounting needs root and loop devices")
def test_a_folder_with_files_is_never_hidden_under_a_disk(place):
    os.makedirs(place.home)
    open(os.path.join(place.home, "old"), "w").close()
    with pytest.raises(disks.DiskError, match="holds files already"):
        disks.ensure(place, 16 * 2 ** 20, uid=1000)


def sandbox_user():
    try:
        return pwd.getpwnam("coursesandbox").pw_name
    except KeyError:
        return None


@pytest.mark.skipif(not ROOT or sandbox_user() is None, reason="needs root and the grader's sandbox user")
def test_the_graders_sandbox_user_reads_no_snapshot_no_finished_grading_and_no_students_folder():
    top = tempfile.mkdtemp(prefix="hub-modes-", dir="/tmp")
    try:
        os.chmod(top, 0o711)  # only the data folder's own modes stand in the way
        data = os.path.join(top, "data")
        os.makedirs(os.path.join(data, "users", "alice", "src", "pkg"))
        with open(os.path.join(data, "users", "alice", "src", "pkg", "answer.py"), "w") as out:
            out.write("alice's answer")
        layout.lay_out(data)
        grading.snapshot(data, os.path.join(data, "snapshots", "first"), ["alice"])
        finished = os.path.join(data, "grades", "first")
        os.makedirs(os.path.join(finished, "alice"))
        with open(os.path.join(finished, "alice", "results.json"), "w") as out:
            out.write("{}")
        os.chmod(finished, 0o700)  # as hub_grade leaves a grading once done
        for path in (os.path.join(data, "snapshots", "first", "alice", "pkg", "answer.py"),
                     os.path.join(data, "users", "alice", "src", "pkg", "answer.py"),
                     os.path.join(finished, "alice", "results.json")):
            tried = subprocess.run(["runuser", "-u", "coursesandbox", "--", "cat", path],
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            assert tried.returncode != 0 and "Permission denied" in tried.stderr, path
        reach = subprocess.run(["runuser", "-u", "coursesandbox", "--", "test", "-x", os.path.join(data, "grades")])
        assert reach.returncode == 0  # the grading under way stays reachable for its own runs
    finally:
        subprocess.run(["chmod", "-R", "u+rwx", top])
        shutil.rmtree(top)
