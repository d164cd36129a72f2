"""What a grading leaves when it is killed (SIGKILL: no clean-up of its own), found and ended by
the next one, or by itself once it was interrupted.

A grading marks itself: the grader starts (execs itself) with GRADER_VAR=<its pid> in its
environment (`marked`; /proc/<pid>/environ shows only what a process was exec'd with), which every
trusted process it starts inherits (rostest, the master, the simulators, the checks, the
builds). A grading is *live* while the process of that pid carries the same mark, so a pid
reused by another program does not keep a dead grading's processes alive. What a dead grading
leaves, and how each is found:

- its trusted processes (rostest and everything below it outlive a killed grader): by the mark;
- its student processes: inside a run's PID namespace they die with the namespace's init,
  whose keeper dies with its check (bubblewrap's --die-with-parent); without namespaces
  (isolation `user only`) by their real group, the grading's own (policy.grading_gid);
- its pids cgroups (`course-sandbox-<pid>-<n>`, made by a check or the grader): those whose
  creating process is gone have their members killed and are removed.

Its work folders are the output folder's (course_grader.runner: a grading's pid file there).
Processes of a live grading, or of anything else, are never touched: nor those of another PID
namespace (a container's gradings, marked with the pids of their own namespace).
"""
from __future__ import annotations

import os
import re
import signal
from typing import Callable, Dict, Iterable, List, Optional

from course_sandbox import pids_cgroup, procs
from course_sandbox.policy import GRADING_GID_BASE, PID_SPAN

GRADER_VAR = "COURSE_GRADER_PID"
_CGROUP_NAME = re.compile(r"^%s(\d+)-\d+$" % re.escape(pids_cgroup.NAME_PREFIX))
KILL_ROUNDS = 20


def marked(env: Dict[str, str]) -> Dict[str, str]:
    """`env` marked as this process's grading: exec this process with it."""
    return dict(env, **{GRADER_VAR: str(os.getpid())})


def is_marked(environ: Optional[Dict[str, str]] = None) -> bool:
    """Whether this process was exec'd marked as a grading of its own (read from the environment
    Python started with, never /proc: a re-exec decided on it cannot loop)."""
    return (os.environ if environ is None else environ).get(GRADER_VAR) == str(os.getpid())


def grading_of(pid: int) -> Optional[int]:
    """The grader pid a process is marked with, or None."""
    prefix = ("%s=" % GRADER_VAR).encode()
    for item in procs.environ(pid):
        if item.startswith(prefix):
            try:
                return int(item[len(prefix):])
            except ValueError:
                return None
    return None


def is_live_grader(pid: int) -> bool:
    return grading_of(pid) == pid


def end_all(find: Callable[[], Iterable[int]], rounds: int = KILL_ROUNDS) -> int:
    """Freeze, then kill, the processes `find()` names, round after round until none are left (a
    forking process cannot outrun a frozen set); how many were killed."""
    killed = set()
    for _ in range(rounds):
        pids = set(find()) - {os.getpid()}
        if not pids:
            break
        for sig in (signal.SIGSTOP, signal.SIGKILL):
            procs.signal_all(pids, sig)
        killed |= pids
    return len(killed)


def _grading_gid_owner(gid: Optional[int]) -> Optional[int]:
    """The grader pid a grading group was made for (policy.grading_gid), or None for another group."""
    if gid is None or gid < GRADING_GID_BASE:
        return None
    return (gid - GRADING_GID_BASE) % PID_SPAN


def dead_gradings_processes() -> List[int]:
    """Processes marked by a grading that is no longer live, or running in a dead grading's group."""
    found = []
    live = {}

    def dead(grader: int) -> bool:
        if grader not in live:
            live[grader] = is_live_grader(grader)
        return not live[grader]
    # This PID namespace's processes only: a grading in a container is marked with its pid there,
    # which names another process (or none) here, and is live all the same.
    for pid in procs.local_pids():
        if pid == os.getpid():
            continue
        grader = grading_of(pid)
        if grader is None:
            grader = _grading_gid_owner(procs.real_group(pid))
        if grader is not None and dead(grader):
            found.append(pid)
    return found


def stale_cgroups(parent: Optional[str]) -> List[pids_cgroup.PidsCgroup]:
    """The sandbox pids cgroups under `parent` whose creating process is gone (or a zombie: killed
    by the sweep, not yet reaped by its new parent)."""
    if parent is None or not os.path.isdir(parent):
        return []
    found = []
    for name in sorted(os.listdir(parent)):
        match = _CGROUP_NAME.match(name)
        if match and not procs.running(int(match.group(1))):
            found.append(pids_cgroup.PidsCgroup(os.path.join(parent, name)))
    return found


def sweep() -> str:
    """End what dead gradings left on this machine: their processes, then their pids cgroups
    (members killed, folder removed). Returns what was done, in words ("" when nothing)."""
    processes = end_all(dead_gradings_processes)
    groups = stale_cgroups(pids_cgroup.own_parent())
    removed = 0
    for group in groups:
        end_all(group.members)
        removed += group.remove_when_empty()
    said = []
    if processes:
        said.append("%d process(es)" % processes)
    if removed:
        said.append("%d pids cgroup(s)" % removed)
    return " and ".join(said)
