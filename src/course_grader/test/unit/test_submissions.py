"""Submissions: names, safe unpacking, packages at any depth, scripts rosrun cannot start."""
import io
import os
import stat
import tarfile
import zipfile

import pytest

from course_grader import submissions
from course_grader.submissions import Submission, UnsafeArchive

PACKAGE_XML = '<?xml version="1.0"?><package format="2"><name>%s</name><version>0.0.1</version></package>'


def _zip(path, members):
    """members: (name, text, mode)"""
    with zipfile.ZipFile(path, "w") as zf:
        for name, text, mode in members:
            info = zipfile.ZipInfo(name)
            info.external_attr = (stat.S_IFREG | mode) << 16
            zf.writestr(info, text)


def test_student_names_from_paths():
    assert submissions.student_name("/x/alice.tar.gz") == "alice"
    assert submissions.student_name("/x/Bob Smith.zip") == "Bob_Smith"
    assert submissions.student_name("/x/carol/") == "carol"
    names = [s.name for s in submissions.named(["/a/dan.zip", "/b/dan"])]
    assert names == ["dan", "dan-2"]


def test_zip_keeps_executable_bits_at_any_depth(tmp_path):
    archive = tmp_path / "alice.zip"
    _zip(archive, [("ws/src/chatter/package.xml", PACKAGE_XML % "chatter", 0o644),
                   ("ws/src/chatter/scripts/talker.py", "#!/usr/bin/env python3\n", 0o755),
                   ("ws/src/chatter/scripts/listener.py", "#!/usr/bin/env python3\n", 0o644)])
    dest = submissions.unpack(Submission("alice", str(archive)), str(tmp_path / "out"))
    scripts = os.path.join(dest, "ws/src/chatter/scripts")
    assert os.access(os.path.join(scripts, "talker.py"), os.X_OK)
    assert not os.access(os.path.join(scripts, "listener.py"), os.X_OK)
    assert [p.name for p in submissions.find_packages(dest)] == ["chatter"]


@pytest.mark.parametrize("evil", ["../escape.txt", "/etc/evil.txt", "a/../../escape.txt"])
def test_zip_path_traversal_is_refused(tmp_path, evil):
    archive = tmp_path / "evil.zip"
    _zip(archive, [(evil, "x", 0o644)])
    with pytest.raises(UnsafeArchive):
        submissions.unpack(Submission("evil", str(archive)), str(tmp_path / "out"))
    assert not (tmp_path / "escape.txt").exists()


def test_zip_size_limit(tmp_path):
    archive = tmp_path / "big.zip"
    _zip(archive, [("big.txt", "0" * 10000, 0o644)])
    with pytest.raises(UnsafeArchive):
        submissions.unpack_zip(str(archive), str(tmp_path / "out"), max_bytes=1000)


def test_tar_leaves_links_out_and_refuses_traversal(tmp_path):
    archive = tmp_path / "bob.tar.gz"
    with tarfile.open(archive, "w:gz") as tf:
        data = (PACKAGE_XML % "my_chatter").encode()
        info = tarfile.TarInfo("src/my_chatter/package.xml")
        info.size = len(data)
        tf.addfile(info, io.BytesIO(data))
        link = tarfile.TarInfo("src/my_chatter/passwd")
        link.type = tarfile.SYMTYPE
        link.linkname = "/etc/passwd"
        tf.addfile(link)
    dest = submissions.unpack(Submission("bob", str(archive)), str(tmp_path / "out"))
    assert not os.path.lexists(os.path.join(dest, "src/my_chatter/passwd"))
    assert [p.name for p in submissions.find_packages(dest)] == ["my_chatter"]
    evil = tmp_path / "evil.tar.gz"
    with tarfile.open(evil, "w:gz") as tf:
        info = tarfile.TarInfo("../../escape.txt")
        info.size = 1
        tf.addfile(info, io.BytesIO(b"x"))
    with pytest.raises(UnsafeArchive):
        submissions.unpack(Submission("evil", str(evil)), str(tmp_path / "out2"))


def test_find_packages_skips_build_and_devel_and_reports_unreadable(tmp_path):
    (tmp_path / "ws/src/a").mkdir(parents=True)
    (tmp_path / "ws/src/a/package.xml").write_text(PACKAGE_XML % "a")
    (tmp_path / "ws/build/a").mkdir(parents=True)
    (tmp_path / "ws/build/a/package.xml").write_text(PACKAGE_XML % "a")
    (tmp_path / "ws/src/broken").mkdir()
    (tmp_path / "ws/src/broken/package.xml").write_text("<package><name>")
    found = submissions.find_packages(str(tmp_path))
    assert [p.name for p in found] == ["a", None]
    assert "cannot be read" in found[1].problem


def test_class_folder_entries(tmp_path):
    (tmp_path / "alice").mkdir()
    (tmp_path / "bob.zip").write_bytes(b"")
    (tmp_path / "notes.txt").write_text("x")
    assert [s.name for s in submissions.class_submissions(str(tmp_path))] == ["alice", "bob"]


def test_a_folder_holding_only_an_archive_gets_it_unpacked(tmp_path):
    upload = tmp_path / "submission"
    upload.mkdir()
    _zip(upload / "lab2.zip", [("chatter/package.xml", PACKAGE_XML % "chatter", 0o644)])
    dest = submissions.unpack(Submission("s", str(upload)), str(tmp_path / "out"))
    assert submissions.find_packages(dest) == []
    assert submissions.unpack_nested(dest) == [os.path.join(dest, "lab2_unpacked")]
    assert [p.name for p in submissions.find_packages(dest)] == ["chatter"]
