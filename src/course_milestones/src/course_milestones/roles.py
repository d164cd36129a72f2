"""Which of a student's executables plays which part (the publisher, the subscriber, the server)
when the text does not name the scripts: start them, ask the master what each registered, and
tie each registered node to the process that started it (the node's pid, via its XML-RPC API)."""
from __future__ import annotations

import os
import signal
import subprocess
import time
import xmlrpc.client
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence

import rosgraph

from course_milestones.discovery import Registration, package_dir, system_state
from course_testkit.artifacts import artifact_path
from course_testkit.nodes import NodeProcess

CALLER = "/course_milestone"
# What every rospy node registers: not worth naming to a student.
_ROUTINE = ("/rosout", "/get_loggers", "/set_logger_level")
# What rospy prints when the master stops a node because a newer one took its name.
SAME_NAME = "new node registered with same name"


class Started(NamedTuple):
    """One student executable we started: its file, process and log."""

    path: str
    node: NodeProcess
    log: str

    @property
    def name(self) -> str:
        return os.path.basename(self.path)

    def output(self) -> str:
        with open(self.log, errors="replace") as f:
            return f.read()


def start(path: str, args: Sequence[str] = ()) -> Started:
    """Start one executable with a pipe as stdin (for typed lines) and its output in an artifact log."""
    log = artifact_path(os.path.basename(path))
    return Started(path, NodeProcess([path] + list(args), stdin=subprocess.PIPE, log_path=log), log)


def stop_all(started: Sequence[Started]) -> None:
    """End of input, then Ctrl+C: a rospy node blocked in input() ignores SIGINT (rospy's handler
    swallows the KeyboardInterrupt and the read resumes) until its input ends."""
    for s in started:
        try:
            s.node.proc.stdin.close()
            os.killpg(s.node.proc.pid, signal.SIGINT)  # all at once: each takes a while to shut down
        except (OSError, ProcessLookupError):
            pass
    for s in started:
        s.node.stop()


def registrations_of(started: Started, known: Dict[str, int]) -> List[Registration]:
    """What the nodes this process (or its children) registered, per node; `known` caches
    node URI -> process group."""
    regs = []
    master = rosgraph.Master(CALLER)
    for node, reg in system_state(CALLER).items():
        try:
            uri = master.lookupNode(node)
        except Exception:  # noqa: BLE001 - the node went away meanwhile
            continue
        if uri not in known:  # by URI: a node started under a name already taken replaces the old one
            known[uri] = _process_group(uri)
        if known[uri] == started.node.proc.pid:
            regs.append(reg)
    return regs


def _process_group(uri: str) -> int:
    try:
        _, _, pid = xmlrpc.client.ServerProxy(uri).getPid(CALLER)
        return os.getpgid(pid)
    except Exception:  # noqa: BLE001 - the node went away, or is not on this machine
        return -1


def find_role(started: Sequence[Started], condition: Callable[[Registration], bool], timeout: float,
              known: Dict[str, int], settle: Optional[float] = None) -> Optional[Started]:
    """The first process with a node whose registration satisfies `condition`; None after `timeout`,
    once every process has exited, or (with `settle`) once each has had a node registered for
    `settle` seconds without satisfying it."""
    deadline = time.monotonic() + timeout
    first_seen: Dict[int, float] = {}
    while True:
        now = time.monotonic()
        waiting = False
        for s in started:
            regs = registrations_of(s, known)
            if any(condition(r) for r in regs):
                return s
            if regs:
                first_seen.setdefault(s.node.proc.pid, now)
            seen = first_seen.get(s.node.proc.pid)
            if s.node.running() and (settle is None or seen is None or now - seen < settle):
                waiting = True
        if not waiting or now > deadline:
            return None
        time.sleep(0.1)


def describe(started: Sequence[Started], known: Dict[str, int]) -> str:
    """What each started executable did, for a failure message: 'a.py publishes /x; b.py exited (code 1)'."""
    parts = []
    for s in started:
        regs = registrations_of(s, known)
        if not s.node.running() and not regs:
            parts.append("%s exited (code %s)%s" % (s.name, s.node.proc.returncode, last_words(s)))
            continue
        words = []
        for kind in ("publishes", "subscribes", "services"):
            names = sorted({n for r in regs for n in getattr(r, kind) if not n.endswith(_ROUTINE)})
            if names:
                words.append("%s %s" % ("offers" if kind == "services" else kind, ", ".join(names)))
        parts.append("%s %s" % (s.name, " and ".join(words) if words else "registered nothing"))
    return "; ".join(parts) or "(no executables)"


def chmod_hint(pkg: str) -> str:
    """' (not executable: a.py, b.py: run chmod +x on them)' when there are such scripts, else ''."""
    names = not_executable(pkg)
    return " (not executable: %s: run chmod +x on them)" % ", ".join(names) if names else ""


def servers_first(paths: Sequence[str]) -> List[str]:
    """`paths` with the likely service servers first (source mentions rospy.Service, name says
    server): only the order of trying changes, and a client tried first only costs time."""
    def key(path: str):
        try:
            with open(path, errors="replace") as f:
                serves = "Service(" in f.read()
        except OSError:
            serves = False
        return (not serves, "server" not in os.path.basename(path))
    return sorted(paths, key=key)


def last_words(started: Started) -> str:
    """The end of a process's output, for a failure message (with a hint when rospy stopped it
    because another node took its name)."""
    try:
        tail = started.output().strip()[-200:]
    except OSError:
        return ""
    if not tail:
        return ""
    hint = ""
    if SAME_NAME in tail:
        hint = (" (another node took its name: give each node its own name, e.g. from its argument, "
                "or rospy.init_node(..., anonymous=True))")
    return ", its output ending with %r%s" % (tail, hint)


def not_executable(pkg: str) -> List[str]:
    """Python scripts in the package that rosrun cannot run because they lack the executable bit
    (the text's `chmod +x *.py` step)."""
    found = []
    for dirpath, dirnames, filenames in os.walk(package_dir(pkg)):
        dirnames[:] = [d for d in dirnames if not d.startswith(".") and d not in ("test", "tests", "build")]
        for name in filenames:
            path = os.path.join(dirpath, name)
            if name.endswith(".py") and name not in ("setup.py", "__init__.py") and not os.access(path, os.X_OK) \
                    and _has_main(path):
                found.append(name)
    return sorted(found)


def _has_main(path: str) -> bool:
    try:
        with open(path, errors="replace") as f:
            return "__main__" in f.read()
    except OSError:
        return False
