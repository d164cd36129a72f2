"""The hub's data folder: its layout and modes, made at the hub's start, at every spawn and by
`hub_grade`, whatever they were.

Root's alone: the students' disks and mount points (`disks/`, `users/`), the snapshots of every
grading (`snapshots/`); the grader's sandbox user passes through the data folder and `grades/`
to the grading under way only (course_hub.grade_cli closes each grading's folder when it is
done), so a later grading's student code reads no snapshot, finished grading or student folder.
The hub's own files (database, cookie secret, password file, hand-out sheet) are 0600 in the
data folder (make hub runs JupyterHub with umask 077).
"""
from __future__ import annotations

import os
from typing import Dict


def data_modes(data: str) -> Dict[str, int]:
    """The data folder's layout: folder -> mode."""
    return {data: 0o711, os.path.join(data, "users"): 0o700, os.path.join(data, "disks"): 0o700,
            os.path.join(data, "snapshots"): 0o700, os.path.join(data, "grades"): 0o711}


def lay_out(data: str) -> None:
    """Make the data folder's layout (data_modes) and set its modes."""
    for folder, mode in data_modes(data).items():
        os.makedirs(folder, mode=mode, exist_ok=True)
        os.chmod(folder, mode)
