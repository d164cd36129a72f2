"""Copying a run's own logs out of the student's folder: regular files only, never through a
link, each cut to its end, a bounded number."""
import os

from course_grader.student_files import copy_logs


def test_logs_are_copied_with_their_folders(tmp_path):
    source, target = tmp_path / "log", tmp_path / "out"
    (source / "latest").mkdir(parents=True)
    (source / "talker-1.log").write_text("hello\n")
    (source / "latest" / "rosout.log").write_text("rosout\n")
    assert sorted(copy_logs(str(source), str(target))) == ["latest/rosout.log", "talker-1.log"]
    assert (target / "talker-1.log").read_text() == "hello\n"
    assert (target / "latest" / "rosout.log").read_text() == "rosout\n"


def test_links_pipes_and_a_linked_folder_are_not_followed(tmp_path):
    secret = tmp_path / "grader-secret"
    secret.write_text("not the student's")
    (tmp_path / "grader-dir").mkdir()
    (tmp_path / "grader-dir" / "other.log").write_text("another student's")
    source, target = tmp_path / "log", tmp_path / "out"
    source.mkdir()
    os.symlink(secret, source / "steal.log")
    os.symlink(tmp_path / "grader-dir", source / "dir")
    os.mkfifo(source / "pipe.log")  # opening it for reading would block
    assert copy_logs(str(source), str(target)) == []
    assert not target.exists() or not any(target.rglob("*"))
    os.symlink(tmp_path / "grader-dir", tmp_path / "linked-log")
    assert copy_logs(str(tmp_path / "linked-log"), str(target)) == []


def test_a_big_file_keeps_its_end_and_the_count_is_bounded(tmp_path):
    source, target = tmp_path / "log", tmp_path / "out"
    source.mkdir()
    (source / "big.log").write_bytes(b"x" * 5000 + b"the end\n")
    for i in range(10):
        (source / ("n%02d.log" % i)).write_text("%d\n" % i)
    copied = copy_logs(str(source), str(target), max_files=4, max_bytes=100)
    assert len(copied) == 4
    big = (target / "big.log").read_bytes()
    assert big.endswith(b"the end\n") and b"5008" not in big and b"first 4908 bytes left out" in big


def test_a_missing_folder_copies_nothing(tmp_path):
    assert copy_logs(str(tmp_path / "none"), str(tmp_path / "out")) == []


def test_one_file_is_read_only_without_links_on_its_way(tmp_path):
    from course_grader.student_files import read_file
    (tmp_path / "grader").mkdir()
    (tmp_path / "grader" / "package.xml").write_text("secret")
    (tmp_path / "ws" / "src" / "pkg").mkdir(parents=True)
    (tmp_path / "ws" / "src" / "pkg" / "package.xml").write_text("<package/>")
    os.symlink(tmp_path / "grader", tmp_path / "ws" / "src" / "linked")
    os.mkfifo(tmp_path / "ws" / "src" / "pipe")
    root = str(tmp_path / "ws" / "src")
    assert read_file(root, "pkg/package.xml") == b"<package/>"
    assert read_file(root, "linked/package.xml") is None
    assert read_file(root, "pkg/../linked/package.xml") is None
    assert read_file(root, "pipe") is None
    assert read_file(root, "nothing/package.xml") is None
