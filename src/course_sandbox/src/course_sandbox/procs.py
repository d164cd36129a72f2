"""What /proc says about processes: the tree below one, a PID namespace's members, their pid in
that namespace, their memory and CPU time. Reads only; a process that goes away is skipped."""
from __future__ import annotations

import os
from typing import Dict, Iterable, List, NamedTuple, Optional

PAGE = os.sysconf("SC_PAGE_SIZE")
TICKS = os.sysconf("SC_CLK_TCK")


def pids() -> Iterable[int]:
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            yield int(entry)


def environ(pid: int) -> List[bytes]:
    """The `NAME=value` entries `pid` was exec'd with ([] when it is gone or not ours to read)."""
    try:
        with open("/proc/%d/environ" % pid, "rb") as f:
            return f.read().split(b"\0")
    except OSError:
        return []


def cmdline(pid: int) -> List[str]:
    """`pid`'s command line, word by word ([] when it is gone)."""
    try:
        with open("/proc/%d/cmdline" % pid, "rb") as f:
            return [part.decode(errors="replace") for part in f.read().split(b"\0") if part]
    except OSError:
        return []


def parent(pid: int) -> Optional[int]:
    try:
        with open("/proc/%d/stat" % pid) as f:
            # The command name may hold spaces and parentheses: the fields after the last ')'.
            return int(f.read().rsplit(")", 1)[1].split()[1])
    except (OSError, IndexError, ValueError):
        return None


def running(pid: int) -> bool:
    """Whether `pid` is a process that has not exited (a zombie, exited but not yet reaped, has)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except (OSError, IndexError):
        return False


def descendants(root: int) -> List[int]:
    """The processes below `root` in the parent tree right now (not root itself)."""
    children: Dict[int, List[int]] = {}
    for pid in pids():
        ppid = parent(pid)
        if ppid is not None:
            children.setdefault(ppid, []).append(pid)
    found, todo = [], [root]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def owner(pid: int) -> Optional[int]:
    """The real uid of the process, or None when it is gone."""
    return _real_id(pid, "Uid:")


def real_group(pid: int) -> Optional[int]:
    """The real gid of the process (an unprivileged process cannot change it), or None when it is gone."""
    return _real_id(pid, "Gid:")


def _real_id(pid: int, field: str) -> Optional[int]:
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith(field):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return None


def command_name(pid: int) -> Optional[str]:
    """The process's command name (/proc/<pid>/comm), or None when it is gone."""
    try:
        with open("/proc/%d/comm" % pid) as f:
            return f.read().strip()
    except OSError:
        return None


def pid_namespace(pid: int) -> Optional[str]:
    try:
        return os.readlink("/proc/%d/ns/pid" % pid)
    except OSError:
        return None


def members(namespace: str) -> List[int]:
    """Every process whose PID namespace is `namespace` (as /proc/<pid>/ns/pid names it)."""
    return [pid for pid in pids() if pid_namespace(pid) == namespace]


def local_pids() -> List[int]:
    """The processes of this process's own PID namespace, whose pids mean here what they say: a
    container's (the course image's, a hub student's) or a sandbox's processes number theirs in a
    namespace of their own, and one whose namespace cannot be read is not ours to judge."""
    return members(pid_namespace(os.getpid()) or "")


def namespace_pid(pid: int) -> Optional[int]:
    """The pid `pid` has in its own (innermost) PID namespace."""
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("NSpid:"):
                    return int(line.split()[-1])
    except (OSError, ValueError, IndexError):
        pass
    return None


class Usage(NamedTuple):
    tasks: int  # threads included, as RLIMIT_NPROC counts
    rss_bytes: int
    cpu_seconds: float  # of this process alone (user + system)


def usage(pid: int) -> Optional[Usage]:
    try:
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rsplit(")", 1)[1].split()
        with open("/proc/%d/statm" % pid) as f:
            rss_pages = int(f.read().split()[1])
    except (OSError, IndexError, ValueError):
        return None
    # After the ')' : state(0) ppid(1) ... utime(11) stime(12) ... num_threads(17)
    return Usage(int(fields[17]), rss_pages * PAGE, (int(fields[11]) + int(fields[12])) / TICKS)


def cpu_with_ended_children(pid: int) -> Optional[float]:
    """CPU seconds (user + system) of the process and of its children that ended and were waited
    for: with descendants(), what a process tree used so far, its short-lived steps included."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return None
    # utime(11) stime(12) cutime(13) cstime(14)
    return sum(int(value) for value in fields[11:15]) / TICKS


def proportional_bytes(pid: int) -> Optional[int]:
    """The process's proportional set size (its share of each page it maps): forks that share
    their parent's pages are not counted once each, as their resident sizes would be."""
    try:
        with open("/proc/%d/smaps_rollup" % pid) as f:
            for line in f:
                if line.startswith("Pss:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def signal_all(pids: Iterable[int], sig: int) -> None:
    """Send `sig` to each of `pids`, skipping those gone or not ours."""
    for pid in pids:
        try:
            os.kill(pid, sig)
        except (ProcessLookupError, PermissionError):
            pass
