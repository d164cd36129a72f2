"""Start a student's launch file the way the text does (`roslaunch PKG FILE`), as a process we own.

roslaunch runs against the master of the milestone's rostest (ROS_MASTER_URI is inherited). Its
stdin is a pseudo-terminal, which every node it starts inherits: a keyboard node in the student's
launch file (turtle_teleop_key) gets a terminal to read, and the check can press keys in it.
"""
from __future__ import annotations

import os
from typing import List

from course_milestones.discovery import package_dir
from course_testkit.artifacts import artifact_path
from course_testkit.keyboard import PtyKeyboard

# roslaunch escalates SIGINT -> SIGTERM -> SIGKILL on its nodes within ~17 s; stop it within that.
ROSLAUNCH_STOP_S = 25.0


def launch_files(pkg: str) -> List[str]:
    """Names of the .launch files anywhere in `pkg` (what `roslaunch pkg <TAB>` offers)."""
    found = []
    for dirpath, dirnames, filenames in os.walk(package_dir(pkg)):
        dirnames[:] = [d for d in dirnames if not d.startswith(".")]
        found.extend(f for f in filenames if f.endswith(".launch"))
    return sorted(set(found))


def missing_launch_file(pkg: str, filename: str) -> str:
    """A sentence for the student when `filename` is not in `pkg`, or "" when it is."""
    found = launch_files(pkg)
    if filename in found:
        return ""
    return "no launch file %s in package %s (found: %s)" % (filename, pkg, ", ".join(found) or "none")


class Roslaunch(PtyKeyboard):
    """`roslaunch PKG FILE ARGS...` on a pseudo-terminal, its output in the artifact `<log_name>.log`."""

    def __init__(self, pkg: str, filename: str, log_name: str, args: List[str] = ()) -> None:
        super().__init__(["roslaunch", pkg, filename] + list(args), log_path=artifact_path(log_name))

    def stop(self, timeout: float = ROSLAUNCH_STOP_S):
        return super().stop(timeout)
