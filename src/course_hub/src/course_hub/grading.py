"""Grading from the hub: a read-only snapshot of every student's catkin_ws/src, then each
student's own report copied into their workbench.

    snapshot(data_dir, class_dir, users)   # <class_dir>/<user>/ = a copy of users/<user>/src, read-only
    # rosrun course_grader grade --class <class_dir> --out <grades>: the gradebook keyed by hub user
    publish(grades, data_dir, users, stamp)  # users/<user>/grades/<stamp>/: that user's results only

The snapshot is what the students' folders held at the moment it was taken: later edits change
nothing in it. It copies directories, regular files and symbolic links (as links, never followed:
a student's link to /etc/shadow stays a link the grader does not follow either); anything else (a
FIFO, a socket, a device) is left out and counted, since opening a FIFO would block the copy.

`publish` copies a user's own folder of the grader's output (results.json, the milestones' JUnit,
logs and canvas pictures) and a plain-text summary, never the class's gradebook or report.html,
which name every student. The grades folder is mounted read-only into the user's container
(course_hub.hubconfig), so the student reads it and cannot change it, and sees no one else's.
"""
from __future__ import annotations

import json
import os
import shutil
import stat
from dataclasses import dataclass, field
from typing import Dict, Iterable, List

from course_hub import hubconfig

READ_ONLY_FILE = 0o444
READ_ONLY_DIR = 0o555
SUMMARY = "report.txt"


@dataclass
class SnapshotCount:
    files: int = 0
    skipped: List[str] = field(default_factory=list)  # special files left out, relative paths


def copy_tree(source: str, target: str, count: SnapshotCount, top: str = "") -> None:
    """Copy `source` to `target` (which must not exist): dirs, regular files, links as links."""
    os.makedirs(target)
    with os.scandir(source) as entries:
        for entry in sorted(entries, key=lambda e: e.name):
            rel = os.path.join(top, entry.name)
            dest = os.path.join(target, entry.name)
            mode = entry.stat(follow_symlinks=False).st_mode
            if stat.S_ISLNK(mode):
                os.symlink(os.readlink(entry.path), dest)
            elif stat.S_ISDIR(mode):
                copy_tree(entry.path, dest, count, rel)
            elif stat.S_ISREG(mode):
                shutil.copyfile(entry.path, dest, follow_symlinks=False)
                os.chmod(dest, READ_ONLY_FILE | (0o111 if mode & 0o111 else 0))
                count.files += 1
            else:
                count.skipped.append(rel)


def make_read_only(top: str) -> None:
    """Every directory under `top` (and `top`) 0555; files were made read-only when copied."""
    for folder, dirs, _ in os.walk(top, topdown=False):
        os.chmod(folder, READ_ONLY_DIR)


def snapshot(data_dir: str, class_dir: str, users: Iterable[str]) -> Dict[str, SnapshotCount]:
    """Copy each user's src (data_dir/users/<user>/src) to class_dir/<user>, read-only; class_dir must
    not exist yet. A user with no folder yet (never started a server) gets an empty submission,
    which the grader grades as such."""
    os.makedirs(class_dir)
    counts: Dict[str, SnapshotCount] = {}
    for user in sorted(users):
        src = hubconfig.user_folders(data_dir, user)["src"]
        count = counts[user] = SnapshotCount()
        if os.path.isdir(src):
            copy_tree(src, os.path.join(class_dir, user), count)
        else:
            os.makedirs(os.path.join(class_dir, user))
        make_read_only(os.path.join(class_dir, user))
    os.chmod(class_dir, READ_ONLY_DIR)
    return counts


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


def publish(grades: str, data_dir: str, users: Iterable[str], stamp: str) -> Dict[str, str]:
    """Copy each user's own folder of the grader's output into their grades folder, under
    `stamp`, with report.txt; {user: the folder written}. Users the grader has no folder for
    are left out."""
    written: Dict[str, str] = {}
    for user in sorted(users):
        own = os.path.join(grades, user)
        if not os.path.isdir(own):
            continue
        target_root = hubconfig.user_folders(data_dir, user)["grades"]
        os.makedirs(target_root, mode=0o755, exist_ok=True)
        target = os.path.join(target_root, stamp)
        if os.path.exists(target):
            shutil.rmtree(target)
        shutil.copytree(own, target, symlinks=True)
        results_path = os.path.join(own, "results.json")
        if os.path.isfile(results_path):
            with open(results_path, encoding="utf-8") as stream:
                text = summary(json.load(stream))
            with open(os.path.join(target, SUMMARY), "w", encoding="utf-8") as out:
                out.write("Graded %s\n%s" % (stamp, text))
        for folder, dirs, files in os.walk(target):
            for name in files:
                path = os.path.join(folder, name)
                if not os.path.islink(path):
                    os.chmod(path, 0o644)
            os.chmod(folder, 0o755)
        written[user] = target
    return written
