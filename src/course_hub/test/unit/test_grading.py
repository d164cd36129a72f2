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
    written = grading.publish(str(grades), str(tmp_path / "data"), ["alice", "bob"], "deadline")
    assert list(written) == ["alice"]
    mine = tmp_path / "data" / "users" / "alice" / "grades" / "deadline"
    assert sorted(os.listdir(mine)) == ["chatter", "report.txt", "results.json"]
    assert "PASSED  chatter  (10 / 10)" in (mine / "report.txt").read_text()
    assert "Score: 10 / 10" in (mine / "report.txt").read_text()
