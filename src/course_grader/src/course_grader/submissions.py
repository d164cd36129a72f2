"""What a student handed in: a folder, .zip or .tar.gz holding catkin packages at any depth.

Archives are unpacked safely: no absolute paths, no `..`, no links or device files, a limit on
the total size and the number of files. Executable bits recorded in the archive are kept (a
script without one is the student's bug, reported as such, not silently fixed).
"""
from __future__ import annotations

import os
import re
import shutil
import stat
import tarfile
import zipfile
import xml.etree.ElementTree as ET
from typing import Dict, List, NamedTuple, Optional, Sequence

from course_milestones.scripts import SKIPPED_DIRS

ARCHIVE_SUFFIXES = (".tar.gz", ".tgz", ".zip")
MAX_UNPACKED_BYTES = 200 * 1024 * 1024
MAX_FILES = 20_000
# Folders that are never a student's package sources (a whole catkin_ws may be handed in):
# course_milestones.scripts.SKIPPED_DIRS, shared with the script checks.


class UnsafeArchive(ValueError):
    """The archive would write outside its folder, or is too big."""


class Submission(NamedTuple):
    name: str  # the student: the entry's name without its archive suffix
    path: str  # the folder or archive as handed in


class Package(NamedTuple):
    name: Optional[str]  # None when package.xml cannot be read
    path: str
    problem: str = ""  # why package.xml could not be read


def student_name(path: str) -> str:
    """A file-system-safe student id from a submission's path."""
    base = os.path.basename(os.path.normpath(path))
    for suffix in ARCHIVE_SUFFIXES:
        if base.lower().endswith(suffix):
            base = base[:-len(suffix)]
            break
    return re.sub(r"[^A-Za-z0-9._-]+", "_", base).strip("._") or "submission"


def is_submission(path: str) -> bool:
    return os.path.isdir(path) or path.lower().endswith(ARCHIVE_SUFFIXES)


def class_submissions(folder: str) -> List[Submission]:
    """Every entry of a class folder that can be a submission (folders and archives), sorted."""
    entries = sorted(os.path.join(folder, e) for e in os.listdir(folder) if not e.startswith("."))
    return named([p for p in entries if is_submission(p)])


def named(paths: Sequence[str]) -> List[Submission]:
    """Submissions for these paths, with unique student names (`name`, `name-2`, ...)."""
    seen: Dict[str, int] = {}
    found = []
    for path in paths:
        name = student_name(path)
        seen[name] = seen.get(name, 0) + 1
        found.append(Submission(name if seen[name] == 1 else "%s-%d" % (name, seen[name]), path))
    return found


def _safe_member_path(dest: str, member: str) -> str:
    """Where `member` goes under `dest`; UnsafeArchive if it would leave it."""
    if member.startswith(("/", "\\")) or re.match(r"^[A-Za-z]:", member):
        raise UnsafeArchive("absolute path in the archive: %s" % member)
    target = os.path.realpath(os.path.join(dest, member))
    if os.path.commonpath([target, os.path.realpath(dest)]) != os.path.realpath(dest):
        raise UnsafeArchive("path leaving the archive's folder: %s" % member)
    return target


class _Budget:
    def __init__(self, max_bytes: int, max_files: int) -> None:
        self.max_bytes, self.max_files = max_bytes, max_files
        self.bytes_left, self.files_left = max_bytes, max_files

    def take_bytes(self, size: int) -> None:
        self.bytes_left -= size
        if self.bytes_left < 0:
            raise UnsafeArchive("the archive unpacks to more than %d MB" % (self.max_bytes // 2**20))

    def take_file(self) -> None:
        self.files_left -= 1
        if self.files_left < 0:
            raise UnsafeArchive("the archive holds more than %d files" % self.max_files)


def _copy_stream(source, target: str, mode: int, budget: _Budget) -> None:
    budget.take_file()
    os.makedirs(os.path.dirname(target), exist_ok=True)
    with open(target, "wb") as out:
        for chunk in iter(lambda: source.read(65536), b""):
            budget.take_bytes(len(chunk))
            out.write(chunk)
    os.chmod(target, 0o755 if mode & 0o111 else 0o644)


def unpack_zip(archive: str, dest: str, max_bytes: int = MAX_UNPACKED_BYTES, max_files: int = MAX_FILES) -> None:
    budget = _Budget(max_bytes, max_files)
    with zipfile.ZipFile(archive) as zf:
        for info in zf.infolist():
            mode = info.external_attr >> 16
            target = _safe_member_path(dest, info.filename)
            if info.is_dir():
                os.makedirs(target, exist_ok=True)
                continue
            if stat.S_ISLNK(mode):
                continue  # links could point anywhere: left out
            with zf.open(info) as source:
                _copy_stream(source, target, mode, budget)


def unpack_tar(archive: str, dest: str, max_bytes: int = MAX_UNPACKED_BYTES, max_files: int = MAX_FILES) -> None:
    budget = _Budget(max_bytes, max_files)
    with tarfile.open(archive, "r:*") as tf:
        for member in tf:
            target = _safe_member_path(dest, member.name)
            if member.isdir():
                os.makedirs(target, exist_ok=True)
            elif member.isfile():
                source = tf.extractfile(member)
                if source is not None:
                    with source:
                        _copy_stream(source, target, member.mode, budget)
            # links, devices and fifos are left out


def unpack(submission: Submission, dest: str) -> str:
    """The submission's files under `dest` (archives unpacked, folders copied); returns dest."""
    if os.path.exists(dest):
        shutil.rmtree(dest)
    path = submission.path
    if os.path.isdir(path):
        shutil.copytree(path, dest, symlinks=True,
                        ignore=shutil.ignore_patterns(*SKIPPED_DIRS))
        return dest
    os.makedirs(dest)
    if path.lower().endswith(".zip"):
        unpack_zip(path, dest)
    else:
        unpack_tar(path, dest)
    return dest


def unpack_nested(dest: str) -> List[str]:
    """Unpack the archives lying at the top of `dest` (a portal such as Gradescope may hand the
    upload over as it came: one .zip in a folder), each into a folder named after it."""
    unpacked = []
    for entry in sorted(os.listdir(dest)):
        path = os.path.join(dest, entry)
        if os.path.isfile(path) and entry.lower().endswith(ARCHIVE_SUFFIXES):
            target = os.path.join(dest, student_name(path) + "_unpacked")
            os.makedirs(target, exist_ok=True)
            (unpack_zip if entry.lower().endswith(".zip") else unpack_tar)(path, target)
            unpacked.append(target)
    return unpacked


def _package_name(package_xml: str) -> Package:
    folder = os.path.dirname(package_xml)
    try:
        name = ET.parse(package_xml).getroot().findtext("name")
    except (ET.ParseError, OSError) as err:
        return Package(None, folder, "package.xml cannot be read: %s" % err)
    if not name or not name.strip():
        return Package(None, folder, "package.xml has no <name>")
    return Package(name.strip(), folder)


def find_packages(root: str) -> List[Package]:
    """The catkin packages under `root`, at any depth (a folder with package.xml is one package,
    and nothing below it is searched, as catkin does; CATKIN_IGNORE hides a folder)."""
    found = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("."))
        if "CATKIN_IGNORE" in files:
            dirs[:] = []
            continue
        if "package.xml" in files:
            found.append(_package_name(os.path.join(folder, "package.xml")))
            dirs[:] = []
    return found


