"""course-lint's probe: what a Python process of the reference's lint run executed, recorded as it
happens. It runs inside the grader's sandbox, in the processes of the reference's run only; the
lint's side (course_lint.ran) lays the probe out and reads what it recorded.

How it gets there (docs/course_lint.md, "How not run is measured"): course-lint hands the grader
the reference with one more package, course_lint_probe, whose catkin environment hook puts a folder
holding a sitecustomize.py first on PYTHONPATH and names the folder for the records
($COURSE_LINT_DATA). The grader sources an overlay's devel/setup.bash for the student's processes
alone (its own side never sources it), so every Python process the run's sandbox starts, and no
other, imports sitecustomize, which calls start(). A real grading never sees the package.

In each such process:
- every file under the workspace's src/ that it opens is recorded (an audit hook on "open"):
  roslaunch reading a launch file, and the launch files that one includes;
- coverage.py (Debian's python3-coverage) measures the lines it runs of the files under src/ (a
  student's node, a module it imports; in every Python process, not only the workspace's
  programs: `python3 -m`, or a tool importing a student's module, runs them too).

A check ends a node with SIGKILL once its verdict is in, and coverage.py writes its data only at
exit: so the lines are written out here as they are first measured. coverage.py calls a plugin's
dynamic_context() at every function call of every thread (its public hook for contexts); this one
never starts a context, it writes the lines coverage.py has measured since the last call, when
there are new ones. A line that does something a check can see mostly ends in a call of Python code (a
publish, rospy's log, a service's reply), so it is written before its effect leaves the process.
A line whose effect is a call of C code alone (print()) gets no call event: a thread of the probe,
started before coverage.py so that it is not measured itself, writes what is new every
WRITE_INTERVAL_S, and the process's own next Python call anywhere writes it sooner. So a process
killed within WRITE_INTERVAL_S of such a line, with no Python call meanwhile, loses that line.

Each process appends to a file of its own, `py.<pid namespace>.<pid>.<random>` in $COURSE_LINT_DATA,
lines of tab-separated words:
    start   <pid namespace> <pid> 1 <argv as JSON>
    open    <path>
    lines   <path> <line numbers, space-separated>
    error   <what went wrong>
No ROS import: this must not change what the process does.
"""
from __future__ import annotations

import atexit
import json
import os
import sys
import threading
from typing import Dict, Optional, Set

DATA_VAR = "COURSE_LINT_DATA"  # the folder the records go to
SRC_VAR = "COURSE_LINT_SRC"  # the workspace's src/, whose files are measured
PACKAGE = "course_lint_probe"  # the probe's own package in src/ (course_lint.ran): not measured
WRITE_INTERVAL_S = 0.05  # s: the writing thread's period (see above)

_probe: Optional["Probe"] = None


def pid_namespace() -> str:
    """The inode of this process's pid namespace ("" when unknown): pids repeat across the sandbox's
    namespace and the host's, and the exec log (exec_log.c) names processes the same way."""
    try:
        link = os.readlink("/proc/self/ns/pid")  # "pid:[4026531836]"
    except OSError:
        return ""
    return link[link.find("[") + 1:link.rfind("]")] if "[" in link else ""


def inside(path: str, folder: str) -> bool:
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


class Probe:
    """One process's records: its file, what it has written already."""

    def __init__(self, fd: int, src: str) -> None:
        self.fd = fd
        self.src = src
        self.coverage = None  # the coverage.Coverage measuring this process, once started
        self.lock = threading.Lock()
        self.count = 0  # lines measured when last written
        self.written: Dict[str, Set[int]] = {}
        self.opened: Set[str] = set()

    def write(self, text: str) -> None:
        os.write(self.fd, text.encode("utf-8", "surrogateescape"))

    def audit(self, event: str, args) -> None:
        """sys.addaudithook's hook: files under src/ that this process opens. It must never raise
        (an audit hook's exception aborts what was being done)."""
        if event != "open" or not args or not isinstance(args[0], (str, os.PathLike)):
            return
        try:
            path = os.path.abspath(os.fspath(args[0]))
            if path in self.opened or not inside(path, self.src):
                return
            self.opened.add(path)
            self.write("open\t%s\n" % path)
        except Exception:  # noqa: BLE001
            pass

    def flush(self) -> None:
        """Write the lines coverage.py has measured since the last time (nothing when none are new).
        Its collector keeps, per measured file, the line numbers seen (a dict or a set); they only
        grow while nothing saves them, which nothing here does."""
        if self.coverage is None:
            return
        collector = getattr(self.coverage, "_collector", None)
        data = getattr(collector, "data", None)
        if not isinstance(data, dict):
            return
        total = sum(map(len, data.values()))  # C-level: no other thread runs meanwhile
        if total == self.count:
            return
        with self.lock:
            out = []
            for path, lines in list(data.items()):
                new = set(lines) - self.written.setdefault(path, set())
                if new:
                    self.written[path] |= new
                    out.append("lines\t%s\t%s\n" % (path, " ".join(str(n) for n in sorted(new))))
            self.count = total
            if out:
                self.write("".join(out))


def start() -> None:
    """Called by the probe's sitecustomize in every Python process of the reference's run."""
    global _probe
    folder, src = os.environ.get(DATA_VAR), os.environ.get(SRC_VAR)
    if _probe is not None or not folder or not src:
        return
    name = "py.%s.%d.%s" % (pid_namespace() or "0", os.getpid(), os.urandom(4).hex())
    try:
        fd = os.open(os.path.join(folder, name), os.O_WRONLY | os.O_CREAT | os.O_APPEND | os.O_CLOEXEC, 0o644)
    except OSError:
        return  # nowhere to say it: the lint finds no record of this process and trusts none of the run's
    probe = Probe(fd, os.path.realpath(src))
    _probe = probe
    argv = list(getattr(sys, "argv", []) or [])
    probe.write("start\t%s\t%d\t1\t%s\n" % (pid_namespace() or "0", os.getpid(), json.dumps(argv)))
    sys.addaudithook(probe.audit)
    try:
        import coverage
        ticker = threading.Thread(target=_write_every_interval, name="course-lint-probe", daemon=True)
        ticker.start()  # before coverage.py starts: a thread started after it is measured
        cov = coverage.Coverage(data_file=None, config_file=False, include=[os.path.join(probe.src, "*")],
                                omit=[os.path.join(probe.src, PACKAGE, "*")])
        cov.set_option("run:plugins", [__name__])  # coverage_init below: the hook that writes the lines
        probe.coverage = cov
        cov.start()
        atexit.register(probe.flush)  # after coverage's own: runs first, while it still measures
    except Exception as err:  # noqa: BLE001 - the process must run on; the lint learns it was not measured
        probe.coverage = None
        probe.write("error\t%s: %s\n" % (type(err).__name__, str(err).replace("\n", " ")))


def _write_every_interval() -> None:
    stop = threading.Event()  # never set: the thread ends with the process
    while not stop.wait(WRITE_INTERVAL_S):
        _write_new_lines(None)


def _write_new_lines(frame) -> None:  # noqa: ARG001 - coverage.py's dynamic_context(frame)
    """The plugin's dynamic_context: write the lines measured since the last call; start no context."""
    probe = _probe
    if probe is not None:
        try:
            probe.flush()
        except Exception:  # noqa: BLE001 - never break the measured program
            pass
    return None


def coverage_init(reg, options) -> None:  # noqa: ARG001 - coverage.py's plugin entry point
    """coverage.py's plugin loader calls this (run:plugins names this module): a plugin whose
    dynamic_context, called at every function call, writes what was measured since the last one."""
    import coverage

    class NewLinesWriter(coverage.CoveragePlugin):
        def dynamic_context(self, frame):
            return _write_new_lines(frame)
    reg.add_dynamic_context(NewLinesWriter())
