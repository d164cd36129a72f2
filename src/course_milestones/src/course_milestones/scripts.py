"""Scripts rosrun cannot start, said in words a student can act on.

One detector for the whole course: the checks append its sentences to a failure (a student
running `rostest` alone sees them) and the grader adds the ones a check did not already say.
Two mistakes are common in the labs: a `#!` script handed in without its executable bit (the
texts' `chmod +x` step), and a `#!` line saved with Windows line endings. Pure file reading.
"""
from __future__ import annotations

import os
from typing import List

from course_milestones import causes

# Build products and tool folders: never a student's script.
SKIPPED_DIRS = {"build", "devel", "install", "logs", ".git", "__pycache__", ".catkin_tools", "__MACOSX"}
# Larger files are data, not scripts.
MAX_SCRIPT_BYTES = 1024 * 1024


def _first_line(path: str) -> bytes:
    try:
        if not os.path.isfile(path) or os.path.getsize(path) > MAX_SCRIPT_BYTES:
            return b""
        with open(path, "rb") as f:
            return f.readline(512)
    except OSError:
        return b""


def script_problems(package_dir: str) -> List[str]:
    """One sentence per problem: a #! line without the executable bit, or a #! line ending in a
    carriage return. Paths are given from the package's name down (chatter/scripts/talker.py)."""
    problems = []
    for folder, dirs, files in os.walk(package_dir):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("."))
        for name in sorted(files):
            path = os.path.join(folder, name)
            first = _first_line(path)
            if not first.startswith(b"#!"):
                continue
            rel = os.path.relpath(path, os.path.dirname(package_dir))
            if not os.access(path, os.X_OK):
                problems.append(causes.finding(
                    "not_executable", "%s starts with #! but is not executable, so rosrun cannot start it "
                                      "(chmod +x %s, and keep the bit in what you hand in)" % (rel, name)))
            if first.rstrip(b"\n").endswith(b"\r"):
                problems.append(causes.finding(
                    "windows_line_endings", "%s has Windows line endings: its #! line asks for '%s\\r', which does not "
                                "exist (convert it to Unix line endings, e.g. dos2unix %s)"
                                % (rel, (first[2:].decode(errors="replace").split() or ["?"])[-1], name)))
    return problems
