"""What a sandbox allows: the paths it may write, the paths it must not see, its limits, the user
it runs as and the isolation in force. A policy is plain data, written by the trusted grader as
JSON and read by the trusted check that starts student processes (`COURSE_SANDBOX_POLICY` names
the file); nothing in it comes from the student except `student_env`, which is only ever handed
back to the student's own processes.
"""
from __future__ import annotations

import grp
import json
import os
from typing import Dict, List, NamedTuple, Optional, Sequence

ENV_VAR = "COURSE_SANDBOX_POLICY"
DEFAULT_USER = "coursesandbox"
# grading_gid: above every group a system hands out, below the overflow and "no group" ids.
GRADING_GID_BASE = 0x70000000
PID_SPAN = 1 << 22  # Linux's largest pid_max
MiB = 1024 * 1024
GiB = 1024 * MiB


class Limits(NamedTuple):
    """Per sandbox: `processes` counts tasks (threads too, as RLIMIT_NPROC does) of the sandbox's
    own user namespace; `memory_bytes` is the resident memory of all its processes together
    (the run is ended past it); `address_space_bytes`, `cpu_seconds` and `file_bytes` hold for
    each process (RLIMIT_AS, RLIMIT_CPU, RLIMIT_FSIZE); `tmp_bytes` is the size of its private /tmp;
    `disk_bytes` is what the policy's `disk_folder` (all of one student's files: its build and
    runs) may take on disk in total (course_sandbox.disk)."""

    processes: int = 1024
    memory_bytes: int = 3 * GiB
    address_space_bytes: int = 8 * GiB
    cpu_seconds: int = 300
    file_bytes: int = 64 * MiB
    tmp_bytes: int = 256 * MiB
    disk_bytes: int = 1 * GiB

    def describe(self) -> str:
        return ("%d processes, %d MiB of memory, %d s of CPU per process, %d MiB per file, %d MiB of disk in "
                "total, %d MiB of /tmp" % (self.processes, self.memory_bytes // MiB, self.cpu_seconds,
                                           self.file_bytes // MiB, self.disk_bytes // MiB, self.tmp_bytes // MiB))


class Policy(NamedTuple):
    """One sandbox's rules.

    level: the isolation in force (course_sandbox.levels), decided once by the grader.
    user: the unprivileged user student code runs as when the grader is root.
    writable: folders the sandbox may write (its overlay workspace, its run's home).
    hidden: folders (or files) it must not see at all (the grader's outputs, the class folder,
        the grader's home); they appear empty.
    readable: folders shown read-only even inside a hidden one (the course workspace).
    home: the student's HOME, ROS_HOME and working directory in a run (one of `writable`).
    student_env: the environment the student's own overlay gives (sourced inside the build's
        sandbox); None: the check's environment (the reference solutions).
    limits: see Limits.
    report: where the trusted side writes what the sandbox saw (limits hit), or "".
    disk_folder: the folder whose total size limits.disk_bytes bounds (the student's work
        folder), or "": no bound in total.
    gid: the real group student code runs with when the user is switched; -1: the user's own.
        Without PID namespaces (isolation `user only`) a grading gives its processes a group of
        their own (grading_gid), so its final sweep ends its processes alone, not another grading's.
    """

    level: str
    user: str = DEFAULT_USER
    writable: Sequence[str] = ()
    hidden: Sequence[str] = ()
    readable: Sequence[str] = ()
    home: str = ""
    student_env: Optional[Dict[str, str]] = None
    limits: Limits = Limits()
    report: str = ""
    gid: int = -1
    disk_folder: str = ""

    def to_json(self) -> str:
        data = self._asdict()
        data["limits"] = self.limits._asdict()
        return json.dumps(data, indent=1, sort_keys=True)

    @classmethod
    def from_json(cls, text: str) -> "Policy":
        data = json.loads(text)
        data["limits"] = Limits(**data.get("limits", {}))
        for key in ("writable", "hidden", "readable"):
            data[key] = list(data.get(key, []))
        return cls(**data)

    def write(self, path: str) -> str:
        with open(path, "w") as f:
            f.write(self.to_json())
        return path


def from_environment(environ: Optional[Dict[str, str]] = None) -> Optional[Policy]:
    """The policy the grader gave this process (`$COURSE_SANDBOX_POLICY`), or None: no sandbox
    (a plain `rostest` by a student or by `make test`)."""
    path = (os.environ if environ is None else environ).get(ENV_VAR)
    if not path:
        return None
    with open(path) as f:
        return Policy.from_json(f.read())


def grading_gid(pid: int) -> int:
    """The real group of one grading's student processes (the grader's pid makes it unique among
    the gradings running at once): a number no group of the system has."""
    gid = GRADING_GID_BASE + pid
    while True:
        try:
            grp.getgrgid(gid)
        except KeyError:
            return gid
        gid += PID_SPAN


def normalised(paths: Sequence[str]) -> List[str]:
    """Absolute, resolved, unique paths, in their given order."""
    seen: List[str] = []
    for path in paths:
        if path:
            real = os.path.realpath(path)
            if real not in seen:
                seen.append(real)
    return seen
