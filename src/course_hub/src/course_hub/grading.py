"""Grading from the hub: a read-only snapshot of every student's catkin_ws/src, then each
student's own report copied into their workbench.

    snapshot(data_dir, class_dir, users)   # <class_dir>/<user>/ = a copy of their src, read-only
    # rosrun course_grader grade --class <class_dir> --out <grades>: the gradebook keyed by hub user
    publish(grades, data_dir, users, stamp)  # their grades/<stamp>/: that user's results only

The snapshot is what the students' folders held at the moment it was taken: later edits change
nothing in it. It is taken by root while the students' servers run, from folders the students
change at will, so it never follows a path: every folder is opened on its parent's descriptor
with O_NOFOLLOW, every file likewise and checked to be a regular file on its own descriptor. A
folder swapped for a link while the copy runs makes that student's copy fail ("not graded",
with the reason), never brings a file from elsewhere into it. Symbolic links are copied as links
(a student's link to /etc/shadow stays a link the grader does not follow either); anything else
(a FIFO, a socket, a device) is left out and counted, since reading a FIFO would block the copy.
A snapshot is bounded (`Bounds`: bytes counted at each file's full size, so a sparse file counts
what it claims, files, depth); past a bound the student is not graded, and told which bound.

`publish` copies a user's own folder of the grader's output (results.json, the milestones' JUnit,
logs and canvas pictures) and a plain-text summary, never the class's gradebook or report.html,
which name every student. The grades folder is mounted read-only into the user's container
(course_hub.containers), so the student reads it and cannot change it, and sees no one else's.
"""
from __future__ import annotations

import errno
import json
import os
import shutil
import stat
from dataclasses import dataclass, field
from typing import Dict, Iterable, List, Optional, Tuple

from course_hub import disks, names

READ_ONLY_FILE = 0o444
READ_ONLY_DIR = 0o555
SUMMARY = "report.txt"
CHUNK = 1 << 20
OPEN_DIR = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC
OPEN_FILE = os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC  # NONBLOCK: a FIFO swapped in never blocks


@dataclass(frozen=True)
class Bounds:
    """What one student's snapshot may hold (as the grader bounds an archive it unpacks)."""

    max_bytes: int = 200 * 2 ** 20
    max_files: int = 20_000
    max_depth: int = 64


class SnapshotRefused(Exception):
    """This student's folder could not be copied as it is; the message is for them and the TA."""


@dataclass
class SnapshotCount:
    files: int = 0
    entries: int = 0  # files and folders, for the bound
    bytes: int = 0
    skipped: List[str] = field(default_factory=list)  # special files left out, relative paths
    error: str = ""  # why this student is not graded ("" when the copy is whole)


def _copy_file(source_fd: int, dest: str, mode: int, count: SnapshotCount, bounds: Bounds, rel: str) -> None:
    size = os.fstat(source_fd).st_size
    if count.bytes + size > bounds.max_bytes:
        raise SnapshotRefused("your catkin_ws/src holds more than %d MB (%s alone is %d MB): remove what the "
                              "packages do not need" % (bounds.max_bytes // 2 ** 20, rel, size // 2 ** 20))
    out = os.open(dest, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o600)
    try:
        left = bounds.max_bytes - count.bytes
        while True:
            chunk = os.read(source_fd, min(CHUNK, left + 1))
            if not chunk:
                break
            if len(chunk) > left:
                raise SnapshotRefused("your catkin_ws/src holds more than %d MB (%s grew while it was copied)"
                                      % (bounds.max_bytes // 2 ** 20, rel))
            os.write(out, chunk)
            left -= len(chunk)
            count.bytes += len(chunk)
        os.fchmod(out, READ_ONLY_FILE | (0o111 if mode & 0o111 else 0))
    finally:
        os.close(out)


def _copy_dir(dir_fd: int, target: str, count: SnapshotCount, bounds: Bounds, top: str, depth: int) -> None:
    """Copy the folder open on `dir_fd` to `target` (made here), never following a path."""
    if depth > bounds.max_depth:
        raise SnapshotRefused("your catkin_ws/src nests folders deeper than %d (%s)" % (bounds.max_depth, top))
    os.mkdir(target, 0o700)
    for name in sorted(os.listdir(dir_fd)):
        rel = os.path.join(top, name)
        dest = os.path.join(target, name)
        mode = os.lstat(name, dir_fd=dir_fd).st_mode
        if stat.S_ISLNK(mode):
            os.symlink(os.readlink(name, dir_fd=dir_fd), dest)
            continue
        if not (stat.S_ISDIR(mode) or stat.S_ISREG(mode)):
            count.skipped.append(rel)
            continue
        count.entries += 1
        if count.entries > bounds.max_files:
            raise SnapshotRefused("your catkin_ws/src holds more than %d files and folders: remove what the "
                                  "packages do not need (a build/ or devel/ folder?)" % bounds.max_files)
        # opened without following, and checked on the descriptor: what was looked at above may
        # have been swapped since
        fd = os.open(name, OPEN_DIR if stat.S_ISDIR(mode) else OPEN_FILE, dir_fd=dir_fd)
        try:
            now = os.fstat(fd).st_mode
            if stat.S_ISDIR(now):
                _copy_dir(fd, dest, count, bounds, rel, depth + 1)
            elif stat.S_ISREG(now):
                _copy_file(fd, dest, now, count, bounds, rel)
                count.files += 1
            else:
                count.skipped.append(rel)
        finally:
            os.close(fd)


def copy_tree(source: str, target: str, count: SnapshotCount, bounds: Bounds = Bounds()) -> None:
    """Copy the folder `source` to `target` (which must not exist): folders, regular files, links
    as links, never following one. SnapshotRefused past a bound; OSError when the folder changed
    under the copy in a way that cannot be copied (a folder swapped for a link)."""
    fd = os.open(source, OPEN_DIR)
    try:
        _copy_dir(fd, target, count, bounds, "", 0)
    finally:
        os.close(fd)


def make_read_only(top: str) -> None:
    """Every directory under `top` (and `top`) 0555; files were made read-only when copied."""
    for folder, dirs, _ in os.walk(top, topdown=False):
        os.chmod(folder, READ_ONLY_DIR)


def user_src(data_dir: str, user: str) -> Optional[str]:
    """The user's src on the host, their disk mounted first when it exists but is not (after the
    machine restarted); None when they never had a server (no disk, no folder)."""
    place = names.places(data_dir, user)
    if os.path.exists(place.disk_image) and not os.path.ismount(place.home):
        disks.mount(place.disk_image, place.home)
    return place.src if os.path.isdir(place.src) else None


def _reason(err: BaseException) -> str:
    if isinstance(err, SnapshotRefused):
        return str(err)
    if isinstance(err, OSError) and err.errno in (errno.ELOOP, errno.ENOTDIR, errno.ENOENT, errno.EINVAL):
        return ("your catkin_ws/src changed while it was copied (%s): a folder was moved or replaced by a link. "
                "Leave it still at the deadline; ask your TA to grade you again" % os.strerror(err.errno))
    return "your catkin_ws/src could not be copied: %s" % err


def snapshot(data_dir: str, class_dir: str, users: Iterable[str],
             bounds: Bounds = Bounds()) -> Dict[str, SnapshotCount]:
    """Copy each user's src to class_dir/<user>, read-only; class_dir must not exist yet. A user
    with no folder yet (never started a server) gets an empty submission, which the grader grades
    as such. A user whose copy fails gets no folder, and their count's `error` says why: the
    others are copied all the same."""
    os.makedirs(class_dir, mode=0o700)
    counts: Dict[str, SnapshotCount] = {}
    for user in sorted(users):
        count = counts[user] = SnapshotCount()
        mine = os.path.join(class_dir, user)
        try:
            src = user_src(data_dir, user)
            if src is None:
                os.makedirs(mine)
            else:
                copy_tree(src, mine, count, bounds)
            make_read_only(mine)
        except (OSError, SnapshotRefused, disks.DiskError) as err:
            count.error = _reason(err)
            if os.path.lexists(mine):
                _remove(mine)
    os.chmod(class_dir, READ_ONLY_DIR)
    return counts


def _remove(top: str) -> None:
    for folder, _, _ in os.walk(top):
        os.chmod(folder, 0o700)
    shutil.rmtree(top)


def summary(results: Dict) -> str:
    """A plain-text report of one student's results.json (Gradescope's format)."""
    lines = ["Score: %s / %s" % (_number(results.get("score", 0)),
                                 _number(sum(float(t.get("max_score", 0)) for t in results.get("tests", []))))]
    for test in results.get("tests", []):
        lines.append("")
        lines.append("%s  %s  (%s / %s)" % (test.get("status", "?").upper(), test.get("name", "?"),
                                            _number(test.get("score", 0)), _number(test.get("max_score", 0))))
        output = str(test.get("output", "")).strip()
        if output:
            lines.extend("    " + line for line in output.splitlines()[:40])
    return "\n".join(lines) + "\n"


def _number(value: object) -> str:
    number = float(value or 0)
    return ("%d" % number) if number == int(number) else ("%.2f" % number)


def publish(grades: str, data_dir: str, users: Iterable[str], stamp: str,
            not_graded: Optional[Dict[str, str]] = None) -> Tuple[Dict[str, str], Dict[str, str]]:
    """Copy each user's own folder of the grader's output into their grades folder, under
    `stamp`, with report.txt; a user in `not_graded` gets only a report.txt saying why. ({user:
    the folder written}, {user: why it could not be written (their disk full, ...)}). Users the
    grader has no folder for, and who are not in `not_graded`, are left out."""
    not_graded = not_graded or {}
    written: Dict[str, str] = {}
    failed: Dict[str, str] = {}
    for user in sorted(users):
        own = os.path.join(grades, user)
        if not os.path.isdir(own) and user not in not_graded:
            continue
        target = os.path.join(names.places(data_dir, user).grades, stamp)
        try:
            _publish_one(own, target, stamp, not_graded.get(user))
            written[user] = target
        except OSError as err:
            failed[user] = str(err)
    return written, failed


def _publish_one(own: str, target: str, stamp: str, not_graded: Optional[str]) -> None:
    os.makedirs(os.path.dirname(target), mode=0o755, exist_ok=True)
    if os.path.exists(target):
        shutil.rmtree(target)
    if not_graded is not None:
        os.makedirs(target)
        text = "Not graded: %s\n" % not_graded
    else:
        shutil.copytree(own, target, symlinks=True)
        text = ""
        results_path = os.path.join(own, "results.json")
        if os.path.isfile(results_path):
            with open(results_path, encoding="utf-8") as stream:
                text = summary(json.load(stream))
    if text:
        with open(os.path.join(target, SUMMARY), "w", encoding="utf-8") as out:
            out.write("Graded %s\n%s" % (stamp, text))
    for folder, dirs, files in os.walk(target):
        for name in files:
            path = os.path.join(folder, name)
            if not os.path.islink(path):
                os.chmod(path, 0o644)
        os.chmod(folder, 0o755)
