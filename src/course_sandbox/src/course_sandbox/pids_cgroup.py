"""A pids cgroup per run: the kernel's own count of one run's processes and threads.

RLIMIT_NPROC bounds a run in its own user namespace, but nothing outside can read the count it
enforces: the watcher's samples of /proc miss the forks still under way (each is counted from
the moment it starts) and, under a fork bomb beside other runs, lag seconds behind, so a run
could hit its limit without the verdict saying so. A pids cgroup counts every task of the run
(`pids.current`), refuses a fork past `pids.max` and counts the refusals (`pids.events`,
"max N"): whether the run reached its limit is then a fact the kernel keeps, not a sample.
Where the grader is not root (user levels) the limit is also per run, not per user.

The trusted side makes one child cgroup of its own cgroup per run (cgroup v1's pids hierarchy,
or v2 where the pids controller is enabled for its children), puts each student process in it
before it becomes the student's (JOIN_SCRIPT: a shell writes its own pid, then execs the
sandbox command), and removes it once the run's processes are gone. Where the machine gives no
writable pids cgroup (a container without cgroup rights, Gradescope's), `create` returns None
and the limit stays RLIMIT_NPROC's with the watcher's samples.
"""
from __future__ import annotations

import functools
import itertools
import os
import signal
import time
from typing import List, Optional

# Writes the shell's own pid into the cgroup ($0), then becomes the command ("$@"); a command that
# could not join is never started.
JOIN_SCRIPT = 'echo $$ > "$0" && exec "$@"'
SHELL = "/bin/sh"
NAME_PREFIX = "course-sandbox-"
_serial = itertools.count()


def parent_from(mountinfo: str, cgroups: str) -> Optional[str]:
    """The folder of this process's own pids cgroup, from /proc/self/mountinfo and
    /proc/self/cgroup: cgroup v1's pids hierarchy if mounted, else the v2 hierarchy; None when
    neither is mounted. Whether it is writable and delegates pids is for `create` to find."""
    own = {}
    for line in cgroups.splitlines():
        parts = line.split(":", 2)
        if len(parts) == 3:
            for controller in parts[1].split(","):
                own[controller] = parts[2]
    v1 = v2 = None
    for line in mountinfo.splitlines():
        fields = line.split()
        if " - " not in line or len(fields) < 5:
            continue
        root, point = fields[3], fields[4]
        after = line.split(" - ", 1)[1].split()
        if len(after) < 3:
            continue
        fstype, options = after[0], after[2].split(",")
        if fstype == "cgroup" and "pids" in options and "pids" in own:
            v1 = _below(point, root, own["pids"])
        elif fstype == "cgroup2" and "" in own:
            v2 = _below(point, root, own[""])
    return v1 or v2


def _below(mount_point: str, mount_root: str, path: str) -> Optional[str]:
    """Where the cgroup `path` (as /proc/self/cgroup names it) is under a mount of the hierarchy
    whose root is `mount_root`; None when the mount does not show it."""
    mount_root = mount_root.rstrip("/")
    if mount_root and not (path == mount_root or path.startswith(mount_root + "/")):
        return None
    relative = path[len(mount_root):].strip("/")
    return os.path.join(mount_point, relative) if relative else mount_point


def _read(path: str) -> str:
    with open(path) as f:
        return f.read()


def own_parent() -> Optional[str]:
    """The folder of this process's own pids cgroup (see parent_from), or None."""
    try:
        return parent_from(_read("/proc/self/mountinfo"), _read("/proc/self/cgroup"))
    except OSError:
        return None


def _delegates_pids(parent: str) -> bool:
    """v1: the hierarchy is pids'. v2: pids is enabled for the children (enabled here if it can be)."""
    control = os.path.join(parent, "cgroup.subtree_control")
    if not os.path.exists(control):
        return os.path.exists(os.path.join(parent, "pids.current")) or os.path.ismount(parent)
    try:
        if "pids" in _read(control).split():
            return True
        with open(control, "w") as f:
            f.write("+pids")
        return True
    except OSError:
        return False


class PidsCgroup:
    """One run's pids cgroup (the folder `path`)."""

    def __init__(self, path: str) -> None:
        self.path = path

    @classmethod
    def create(cls, limit: int) -> Optional["PidsCgroup"]:
        """A new cgroup below this process's own, holding at most `limit` tasks; None where the
        machine gives none."""
        parent = own_parent()
        if parent is None or not _delegates_pids(parent):
            return None
        path = os.path.join(parent, "%s%d-%d" % (NAME_PREFIX, os.getpid(), next(_serial)))
        try:
            os.mkdir(path)
        except OSError:
            return None
        group = cls(path)
        try:
            with open(os.path.join(path, "pids.max"), "w") as f:
                f.write(str(limit))
        except OSError:
            group.remove()
            return None
        return group

    def join_prefix(self) -> List[str]:
        """Put before a command line: the command runs in this cgroup."""
        return [SHELL, "-c", JOIN_SCRIPT, os.path.join(self.path, "cgroup.procs")]

    def tasks(self) -> int:
        """Processes and threads in the cgroup now, forks under way included (pids.current)."""
        try:
            return int(_read(os.path.join(self.path, "pids.current")))
        except (OSError, ValueError):
            return 0

    def refusals(self) -> int:
        """How many forks and thread starts the limit has refused (pids.events' "max")."""
        try:
            for line in _read(os.path.join(self.path, "pids.events")).splitlines():
                key, _, value = line.partition(" ")
                if key == "max":
                    return int(value)
        except (OSError, ValueError):
            pass
        return 0

    def members(self) -> List[int]:
        """The pids of its processes."""
        try:
            return [int(p) for p in _read(os.path.join(self.path, "cgroup.procs")).split()]
        except (OSError, ValueError):
            return []

    def remove(self) -> bool:
        """Remove the (empty) cgroup; False while a process is still in it."""
        try:
            os.rmdir(self.path)
            return True
        except FileNotFoundError:
            return True
        except OSError:
            return False

    def remove_when_empty(self, timeout: float = 5.0) -> bool:
        """Remove the cgroup once the processes killed in it are gone (a killed process leaves
        its cgroup when it is reaped), killing what is still in it meanwhile; False if one never
        goes (the cgroup is left, empty of use)."""
        deadline = time.monotonic() + timeout
        while not self.remove():
            if time.monotonic() > deadline:
                return False
            for pid in self.members():
                try:
                    os.kill(pid, signal.SIGKILL)
                except (ProcessLookupError, PermissionError):
                    pass
            time.sleep(0.01)
        return True


@functools.lru_cache(maxsize=1)
def available() -> bool:
    """Whether this machine gives the grader a pids cgroup per run (probed once: made and removed)."""
    group = PidsCgroup.create(1)
    return group is not None and group.remove()


def describe(in_force: bool, limit: int) -> str:
    return ("each run's processes and threads counted by the kernel in a pids cgroup of its own (%d at most)" % limit
            if in_force else "the process limit (%d) is RLIMIT_NPROC's, seen by the watcher's samples" % limit)
