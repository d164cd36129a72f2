"""Grading from the hub as data: the snapshot (read-only, links kept as links, special files left
out) and each student's own report copied to them, never the class's files."""
from __future__ import annotations

import json
import os
import stat

from course_hub import grading


def student(data, name, files):
    src = data / "users" / name / "src"
    for rel, text in files.items():
        (src / rel).parent.mkdir(parents=True, exist_ok=True)
        (src / rel).write_text(text)
    return src


def test_the_snapshot_is_a_read_only_copy_that_later_edits_do_not_change(tmp_path):
    data = tmp_path / "data"
    src = student(data, "alice", {"chatter/package.xml": "<package/>", "chatter/scripts/talker.py": "print(1)"})
    os.chmod(src / "chatter" / "scripts" / "talker.py", 0o755)
    os.symlink("/etc/shadow", src / "chatter" / "secret")
    os.mkfifo(str(src / "chatter" / "pipe"))
    counts = grading.snapshot(str(data), str(tmp_path / "snap"), ["alice", "bob"])
    assert counts["alice"].files == 2 and counts["alice"].skipped == [os.path.join("chatter", "pipe")]
    copy = tmp_path / "snap" / "alice" / "chatter"
    assert (copy / "package.xml").read_text() == "<package/>"
    assert os.readlink(copy / "secret") == "/etc/shadow"
    assert stat.S_IMODE(os.stat(copy / "scripts" / "talker.py").st_mode) == 0o555
    assert stat.S_IMODE(os.stat(copy / "package.xml").st_mode) == 0o444
    assert stat.S_IMODE(os.stat(copy).st_mode) == 0o555
    assert os.listdir(tmp_path / "snap" / "bob") == []  # never started a server: an empty submission
    (src / "chatter" / "package.xml").write_text("changed after the deadline")
    assert (copy / "package.xml").read_text() == "<package/>"


def test_each_student_gets_their_own_results_and_a_summary_never_the_class_files(tmp_path):
    grades = tmp_path / "grades"
    (grades / "alice" / "chatter").mkdir(parents=True)
    (grades / "alice" / "chatter" / "junit.xml").write_text("<testsuite/>")
    (grades / "alice" / "results.json").write_text(json.dumps({"score": 10, "tests": [
        {"name": "chatter", "score": 10, "max_score": 10, "status": "passed", "output": "ok"}]}))
    (grades / "gradebook.csv").write_text("student,chatter\nalice,10\nbob,0\n")
    (grades / "report.html").write_text("everyone")
    written, failed = grading.publish(str(grades), str(tmp_path / "data"), ["alice", "bob"], "deadline")
    assert failed == {}
    assert list(written) == ["alice"]
    mine = tmp_path / "data" / "users" / "alice" / "grades" / "deadline"
    assert sorted(os.listdir(mine)) == ["chatter", "report.txt", "results.json"]
    assert "PASSED  chatter  (10 / 10)" in (mine / "report.txt").read_text()
    assert "Score: 10 / 10" in (mine / "report.txt").read_text()


def test_a_folder_swapped_for_a_link_while_the_copy_runs_never_brings_a_host_file_in(tmp_path):
    """A student's terminal swaps a folder of their src with a link to the host's secrets in a
    tight loop while root snapshots the class: each try gives her own files or "not graded" with
    the reason, never the secret; bob is copied whatever she does."""
    import threading
    data = tmp_path / "data"
    secrets_dir = tmp_path / "host"
    secrets_dir.mkdir()
    (secrets_dir / "cookie_secret").write_text("HOST SECRET")
    src = student(data, "alice", {"pkg/package.xml": "<package/>", "pkg/scripts/a.py": "1"})
    for i in range(200):
        (src / "pkg" / ("f%03d" % i)).write_text("mine")
    student(data, "bob", {"chatter/package.xml": "<package/>"})
    stop = threading.Event()

    def swap() -> None:
        real, aside, link = src / "pkg", src / "pkg.real", src / "pkg.link"
        while not stop.is_set():
            try:
                os.symlink(secrets_dir, link)
                os.rename(real, aside)
                os.rename(link, real)      # pkg is now the link
                os.rename(real, link)
                os.rename(aside, real)     # pkg is the folder again
                os.unlink(link)
            except OSError:
                pass

    swapper = threading.Thread(target=swap)
    swapper.start()
    outcomes = []
    try:
        for attempt in range(12):
            snap = tmp_path / ("snap%d" % attempt)
            counts = grading.snapshot(str(data), str(snap), ["alice", "bob"])
            assert not counts["bob"].error and (snap / "bob" / "chatter" / "package.xml").exists()
            for folder, _, files in os.walk(snap):
                for name in files:
                    path = os.path.join(folder, name)
                    assert os.path.islink(path) or open(path).read() != "HOST SECRET", path
            outcomes.append(counts["alice"].error or "copied")
            if counts["alice"].error:
                assert "changed while it was copied" in counts["alice"].error
                assert not (snap / "alice").exists()
    finally:
        stop.set()
        swapper.join()
    assert outcomes  # (either outcome may happen; neither may bring the host's file)


def test_a_sparse_file_counts_at_its_full_size_and_the_student_is_told_which_bound(tmp_path):
    data = tmp_path / "data"
    src = student(data, "alice", {"pkg/package.xml": "<package/>"})
    with open(src / "pkg" / "huge.bin", "wb") as sparse:
        sparse.truncate(16 * 2 ** 30)
    student(data, "bob", {"pkg/package.xml": "<package/>"})
    counts = grading.snapshot(str(data), str(tmp_path / "snap"), ["alice", "bob"])
    assert "more than 200 MB (pkg/huge.bin alone is 16384 MB)" in counts["alice"].error
    assert not (tmp_path / "snap" / "alice").exists() and not counts["bob"].error
    used = sum(os.lstat(os.path.join(f, n)).st_blocks * 512 for f, _, ns in os.walk(tmp_path / "snap") for n in ns)
    assert used < 2 ** 20


def test_too_many_files_or_too_deep_is_refused_with_the_bound(tmp_path):
    data = tmp_path / "data"
    src = student(data, "alice", {"pkg/package.xml": "<package/>"})
    for i in range(30):
        (src / "pkg" / str(i)).write_text("x")
    deep = src / "pkg"
    for _ in range(10):
        deep = deep / "d"
    deep.mkdir(parents=True)
    few = grading.Bounds(max_files=20)
    assert "more than 20 files and folders" in grading.snapshot(str(data), str(tmp_path / "a"), ["alice"], few)[
        "alice"].error
    shallow = grading.Bounds(max_depth=5)
    assert "deeper than 5" in grading.snapshot(str(data), str(tmp_path / "b"), ["alice"], shallow)["alice"].error


def test_a_student_not_graded_gets_a_report_saying_why(tmp_path):
    written, _ = grading.publish(str(tmp_path / "grades"), str(tmp_path / "data"), ["alice", "bob"], "deadline",
                              {"alice": "your catkin_ws/src holds more than 200 MB"})
    assert list(written) == ["alice"]
    report = tmp_path / "data" / "users" / "alice" / "grades" / "deadline" / "report.txt"
    assert "Not graded: your catkin_ws/src holds more than 200 MB" in report.read_text()
