"""One sandbox for one milestone run, or one build: the entry points.

RunSandbox (used by the trusted check, course_milestones.students): `prepare(command, env)`
turns a student's command into one that runs inside the run's sandbox, with the student's own
environment; `close()` ends every process in it. A watcher samples the sandbox twice a second:
past the memory limit or near the process limit it ends the run's processes; near the CPU limit
it notes the hit; every DISK_WATCH_INTERVAL_S it measures the student's work folder, and past
its bound in total (course_sandbox.disk) it ends the run's processes; the report (JSON, written by this trusted side) tells the grader which limit
the student's code hit.

run_oneshot (used by the grader's build): a command in a sandbox of its own, to its end.
"""
from __future__ import annotations

import contextlib
import json
import os
import pwd
import select
import signal
import subprocess
import threading
import time
from typing import Callable, Dict, Iterator, List, NamedTuple, Optional, Sequence, Set, Tuple

from course_sandbox import commands, disk, levels, procs
from course_sandbox.pids_cgroup import PidsCgroup
from course_sandbox.access import identity, traverser
from course_sandbox.policy import Policy

WATCH_INTERVAL_S = 0.5
START_TIMEOUT_S = 10.0
KEEPER_EXIT_S = 5.0
# Without a pids cgroup the watcher samples: this share of the process limit counts as having reached it.
PROCESS_SHARE_NOTED = 0.9
# Variables of the trusted side a student process never gets.
TRUSTED_VARS = ("COURSE_ARTIFACTS_DIR", "COURSE_SANDBOX_POLICY", "COURSE_WS_SETUP")
# Variables of the run (its master, its token, output flushed line by line, the quicker distutils
# for a student's roslaunch) the student's processes do get.
# ROS_ETC_DIR: the run's etc/ros (course_checks.core_params), whose roscore.xml every roslaunch
# loads: without it a student's roslaunch runs `rosversion` twice (0.2 CPU s) before its nodes.
RUN_VARS = ("ROS_MASTER_URI", "ROS_HOSTNAME", "ROS_IP", "COURSE_RUN_TOKEN", "PYTHONUNBUFFERED", "LD_PRELOAD",
            "_STDBUF_O", "QT_QPA_PLATFORM", "SETUPTOOLS_USE_DISTUTILS", "ROS_ETC_DIR")
CAPTURE_BYTES = 1024 * 1024
# The environment the trusted process (a check) started with: what it sets later is on purpose.
_STARTING_ENV = dict(os.environ)
CAPTURE_GRACE_S = 0.5


def student_env(policy: Policy, env: Optional[Dict[str, str]] = None,
                started_with: Optional[Dict[str, str]] = None) -> Dict[str, str]:
    """The environment of a student process: the student's own overlay environment (or, for
    the reference, the check's), the run's variables, what the check set on purpose (in `env`,
    or in its own environment since it started: `started_with`, by default the environment
    this process had when the sandbox module was loaded), and its own HOME/ROS_HOME/ROS_LOG_DIR;
    never the trusted side's variables."""
    given = dict(os.environ if env is None else env)
    started_with = _STARTING_ENV if started_with is None else started_with
    base = dict(policy.student_env) if policy.student_env is not None else dict(given)
    for key in RUN_VARS:
        if key in given:
            base[key] = given[key]
        else:
            base.pop(key, None)
    for key, value in given.items():  # e.g. TURTLEBOT3_MODEL, which the text has students export
        if started_with.get(key) != value and key not in ("ROS_HOME", "ROS_LOG_DIR", "HOME"):
            base[key] = value
    for key in TRUSTED_VARS + ("DISPLAY",):
        base.pop(key, None)
    if policy.home:
        base.update(HOME=policy.home, ROS_HOME=policy.home, ROS_LOG_DIR=os.path.join(policy.home, "log"))
    return base


class LimitHits:
    """Which limits the sandbox's processes reached, as the watcher saw them (thread-safe)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.hits: Dict[str, str] = {}
        self.peak_tasks = 0
        self.peak_rss = 0

    def note(self, limit: str, sentence: str) -> None:
        with self._lock:
            self.hits.setdefault(limit, sentence)

    def sample(self, tasks: int, rss: int) -> None:
        with self._lock:
            self.peak_tasks = max(self.peak_tasks, tasks)
            self.peak_rss = max(self.peak_rss, rss)

    def as_dict(self) -> Dict:
        with self._lock:
            return {"hits": dict(self.hits), "peak_tasks": self.peak_tasks, "peak_rss_bytes": self.peak_rss}


class Counted(NamedTuple):
    """What the run's pids cgroup says: its tasks now (forks under way included) and how many
    forks or thread starts its limit refused."""

    tasks: int
    refusals: int


def judge_usage(policy: Policy, usages: Sequence[procs.Usage], hits: LimitHits,
                shared_memory: Callable[[], int] = lambda: 0, counted: Optional[Counted] = None) -> bool:
    """Note the limits `usages` (one sample of the sandbox's processes) reach; True when the run's
    processes must end (memory, processes). Resident sizes count a page shared by forks once per fork, so past the
    limit `shared_memory()` (the proportional total, slower to read) decides.

    Processes: where the run has a pids cgroup (`counted`), the kernel's count decides: a refused
    fork is the limit reached, however few processes a sample shows (forks under way are counted
    but not yet in /proc, and a sample under a fork bomb lags). Without one, the limit is
    RLIMIT_NPROC in the run's own user namespace, and a sample near it decides."""
    limits = policy.limits
    tasks = counted.tasks if counted is not None else sum(u.tasks for u in usages)
    rss = sum(u.rss_bytes for u in usages)
    if rss > limits.memory_bytes:
        rss = min(rss, shared_memory())
    hits.sample(tasks, rss)
    end = False
    if tasks >= limits.processes * PROCESS_SHARE_NOTED or (counted is not None and counted.refusals > 0):
        # A fork bomb at its limit retries fork() in every process: it would starve the other
        # runs of CPU, so its run ends here.
        hits.note("processes", "your code reached the process limit (%d processes and threads); "
                  "all its processes were ended" % limits.processes)
        end = True
    if any(u.cpu_seconds >= limits.cpu_seconds - 1 for u in usages):
        hits.note("cpu", "a process of yours used its %d s of CPU time and was stopped (SIGXCPU)"
                  % limits.cpu_seconds)
    if rss > limits.memory_bytes:
        hits.note("memory", "your processes used more than %d MiB of memory together; they were all ended"
                  % (limits.memory_bytes // (1024 * 1024)))
        end = True
    return end


class RunSandbox:
    """The sandbox of one milestone run (see the module docstring); any thread may use it."""

    def __init__(self, policy: Policy) -> None:
        self.policy = policy
        self.hits = LimitHits()
        self._lock = threading.Lock()
        self._keeper: Optional[subprocess.Popen] = None
        self._init_pid = 0
        self._namespace: Optional[str] = None
        self._entered: List[subprocess.Popen] = []
        self._closed = threading.Event()
        self._released = threading.Event()  # the keeper is gone: its holding thread may end
        self._watcher: Optional[threading.Thread] = None
        self._cgroup: Optional[PidsCgroup] = None
        self._disk = disk.DiskMeter(policy.disk_folder, policy.limits.disk_bytes) if policy.disk_folder else None

    @property
    def level(self) -> str:
        return self.policy.level

    def _start_keeper(self) -> None:
        """Start the keeper and wait for its namespace init (bubblewrap's child, pid 1 inside).

        bubblewrap's --die-with-parent fires when the *thread* that started it ends, so the keeper
        is started by a thread of its own that lives until close(), whichever thread asks first."""
        # Outside the run's pids cgroup: the limit counts the student's processes (and the nsenter
        # each waits under), not the keeper's two.
        argv = commands.keeper_command(self.policy, traverser(*identity(self.policy.level, self.policy.user)))
        started = threading.Event()
        failure: List[BaseException] = []

        def hold() -> None:
            try:
                self._keeper = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                                stderr=subprocess.PIPE, start_new_session=True)
                self._wait_for_init()
            except BaseException as error:  # handed to the caller
                failure.append(error)
                return
            finally:
                started.set()
            self._released.wait()
        threading.Thread(target=hold, name="sandbox-keeper", daemon=True).start()
        started.wait()
        if failure:
            raise failure[0]

    def _wait_for_init(self) -> None:
        """Wait until bubblewrap's child, pid 1 inside, has set the view up and become the
        keeper's init (it is pid 1 from the start, while it still mounts: no process may join
        before it runs KEEPER_INIT)."""
        deadline = time.monotonic() + START_TIMEOUT_S
        while time.monotonic() < deadline:
            for child in procs.descendants(self._keeper.pid):
                if procs.namespace_pid(child) == 1 and procs.command_name(child) == commands.KEEPER_NAME:
                    self._init_pid, self._namespace = child, procs.pid_namespace(child)
                    return
            if self._keeper.poll() is not None:
                break
            time.sleep(0.005)
        code = self._keeper.poll()
        error = (self._keeper.stderr.read() or b"") if code is not None else b""
        self._kill_keeper()
        why = ("its keeper exited with code %s: %s" % (code, error.decode(errors="replace").strip() or "no message")
               if code is not None else "its keeper's init was not up within %g s" % START_TIMEOUT_S)
        raise RuntimeError("the sandbox did not start: %s" % why)

    def _ensure_started(self) -> None:
        with self._lock:
            if self._closed.is_set():
                raise RuntimeError("the sandbox is closed")
            if levels.uses_namespaces(self.level) and self._keeper is None:
                self._start_keeper()
            if self._watcher is None:  # the first start: the run's pids cgroup (where the machine has one)
                self._cgroup = PidsCgroup.create(self.policy.limits.processes)
                self._watcher = threading.Thread(target=self._watch, name="sandbox-watch", daemon=True)
                self._watcher.start()

    def prepare(self, command: Sequence[str], env: Optional[Dict[str, str]] = None,
                cwd: Optional[str] = None) -> Tuple[List[str], Dict[str, str], Optional[str]]:
        """(argv, env, cwd) that run `command` in this run's sandbox as a student process; pass
        them to subprocess.Popen."""
        self._ensure_started()
        cwd = cwd or self.policy.home or "/"
        argv = self._join() + commands.enter_command(self.policy, self._init_pid, command, cwd,
                                                     counted=self._cgroup is not None)
        popen_cwd = None if levels.uses_namespaces(self.level) else cwd
        return argv, dict(student_env(self.policy, env), PWD=cwd), popen_cwd

    def run_captured(self, command: Sequence[str], timeout: float = 30.0,
                     env: Optional[Dict[str, str]] = None) -> Tuple[Optional[int], bytes]:
        """Run `command` in the sandbox to its end: its exit code (None past `timeout`) and its
        standard output (at most 1 MiB; the rest is dropped)."""
        argv, env, cwd = self.prepare(command, env)
        proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                env=env, cwd=cwd, start_new_session=True)
        return _collect(proc, timeout)

    def _join(self) -> List[str]:
        """The prefix that starts a command in the run's pids cgroup (none without one)."""
        return self._cgroup.join_prefix() if self._cgroup is not None else []

    @property
    def counts_processes(self) -> bool:
        """Whether a pids cgroup of its own counts and limits this run's processes."""
        return self._cgroup is not None

    def processes(self) -> List[int]:
        """The host pids of every process in the sandbox (its namespace init excluded); without
        namespaces, those in its pids cgroup, if any."""
        if self._namespace is not None:
            return [pid for pid in procs.members(self._namespace) if pid != self._init_pid]
        return self._cgroup.members() if self._cgroup is not None else []

    def host_pid(self, namespace_pid: int) -> Optional[int]:
        """The host pid of the sandbox's process whose pid inside the sandbox is `namespace_pid`
        (what a node's getPid answers), or None. Without namespaces pids are the same."""
        if self._namespace is None:
            return namespace_pid
        for pid in self.processes():
            if procs.namespace_pid(pid) == namespace_pid:
                return pid
        return None

    def _watch(self) -> None:
        while not self._closed.wait(WATCH_INTERVAL_S):
            if self._sample():
                self.end_processes()
                self.write_report()

    def _sample(self, final: bool = False) -> bool:
        """One look at the sandbox's processes (see judge_usage) and, each disk interval (or
        `final`ly), at the student's files: True when the processes must end."""
        if self._disk is not None and self._disk.over(float("inf") if final else None):
            self.hits.note("disk", disk.sentence(self._disk.limit_bytes))
            return True
        pids = self.processes()
        usages = [u for u in (procs.usage(pid) for pid in pids) if u is not None]
        counted = (Counted(self._cgroup.tasks(), self._cgroup.refusals()) if self._cgroup is not None else None)
        return bool(usages or counted) and judge_usage(
            self.policy, usages, self.hits, lambda: sum(procs.proportional_bytes(pid) or 0 for pid in pids), counted)

    def end_processes(self, rounds: int = 20) -> None:
        """Kill every process in the sandbox now (the keeper stays: later starts still work).
        Each round freezes them all before killing any, so a fork bomb cannot refill the slots
        the kills free.

        nsenter, outside the namespace, stops itself when it sees its child stopped (to pass a
        job-control stop on) and would stay stopped once that child is killed: the nsenters of the
        killed processes are continued at the end, so they report the kill (-9) and exit."""
        entered: Set[int] = set()
        for _ in range(rounds):
            pids = self.processes()
            if not pids:
                break
            if self._namespace is not None:  # without one, the parents outside are the check itself
                entered |= {p for p in (procs.parent(pid) for pid in pids)
                            if p and p not in pids and p != self._init_pid}
            for sig in (signal.SIGSTOP, signal.SIGKILL):
                procs.signal_all(pids, sig)
        procs.signal_all(entered, signal.SIGCONT)

    def _kill_keeper(self) -> None:
        if self._keeper is None:
            return
        for pid in [self._init_pid] if self._init_pid else []:
            try:
                os.kill(pid, signal.SIGKILL)  # the namespace's init: everything in it dies with it
            except (ProcessLookupError, PermissionError):
                pass
        try:  # bubblewrap reaps its init and exits; only if it does not, kill it too
            self._keeper.wait(KEEPER_EXIT_S)
        except subprocess.TimeoutExpired:
            try:
                os.killpg(self._keeper.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            self._keeper.wait()
        self._keeper.stderr.close()

    def write_report(self) -> None:
        if not self.policy.report:
            return
        data = dict(self.hits.as_dict(), level=self.level, processes_counted_by_cgroup=self.counts_processes,
                    isolation=levels.describe(self.level, self.policy.user),
                    limits=self.policy.limits._asdict())
        tmp = self.policy.report + ".tmp"
        with open(tmp, "w") as f:
            json.dump(data, f, indent=1, sort_keys=True)
        os.replace(tmp, self.policy.report)

    def close(self) -> None:
        """End every process of the sandbox, whatever it did, and write the report."""
        if self._closed.is_set():
            return
        self._closed.set()
        if self._watcher is not None:
            self._watcher.join(5)
        # A last look before the end: a run can fail within a watch interval of hitting a limit
        # (a fork bomb that keeps the node from starting a thread), and the verdict must say so.
        self._sample(final=True)
        with self._lock:
            if levels.uses_namespaces(self.level) or self._cgroup is not None:
                # The processes first, so a stopped nsenter is continued and reaps its child: the
                # namespace's init, killed next, cannot finish dying while a member is unreaped.
                self.end_processes()
                self._kill_keeper()
            self._released.set()
            if self._cgroup is not None:
                self._cgroup.remove_when_empty(KEEPER_EXIT_S)
        self.write_report()

    def __enter__(self) -> "RunSandbox":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _collect(proc: subprocess.Popen, timeout: float) -> Tuple[Optional[int], bytes]:
    """A process's exit code (None past `timeout`: it is killed) and its first CAPTURE_BYTES of
    output. Reading stops at end of output, or shortly after the process exits even if something
    it left behind still holds the pipe."""
    fd = proc.stdout.fileno()
    deadline = time.monotonic() + timeout
    data = bytearray()
    exited_at: Optional[float] = None
    while True:
        now = time.monotonic()
        if exited_at is None and proc.poll() is not None:
            exited_at = now
        if now > deadline or (exited_at is not None and now - exited_at > CAPTURE_GRACE_S):
            break
        ready, _, _ = select.select([fd], [], [], 0.05)
        if not ready:
            continue
        chunk = os.read(fd, 65536)
        if not chunk:
            try:
                proc.wait(max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                pass
            break
        data += chunk[:max(0, CAPTURE_BYTES - len(data))]
    code = proc.poll()
    if code is None:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait()
    proc.stdout.close()
    return code, bytes(data)


def run_oneshot(policy: Policy, command: Sequence[str], cwd: str, env: Dict[str, str], log_path: str,
                timeout: float, hits: Optional[LimitHits] = None) -> Optional[int]:
    """Run `command` (a build) in a sandbox of its own with output to `log_path`: its exit code,
    or None past `timeout`. Nothing it started outlives it. Past the policy's disk bound in total
    (`disk_folder`) its processes are ended and `hits` notes "disk"."""
    with open(log_path, "wb") as log, _oneshot(policy, command, cwd, env, stdout=log, stderr=subprocess.STDOUT) as proc:
        stop = threading.Event()
        meter = disk.DiskMeter(policy.disk_folder, policy.limits.disk_bytes) if policy.disk_folder else None

        def over() -> None:
            if hits is not None:
                hits.note("disk", disk.sentence(policy.limits.disk_bytes))
            procs.signal_all(procs.descendants(proc.pid) + [proc.pid], signal.SIGKILL)
        if meter is not None:
            disk.watch(meter, stop, over)
        try:
            code = proc.wait(timeout)
        except subprocess.TimeoutExpired:
            code = None
        stop.set()
        if meter is not None and meter.over(float("inf")):
            over()
        return code


def capture_oneshot(policy: Policy, command: Sequence[str], cwd: str, env: Dict[str, str],
                    timeout: float = 60.0) -> Tuple[Optional[int], bytes]:
    """Run `command` in a sandbox of its own: exit code (None past `timeout`) and stdout (1 MiB at most)."""
    with _oneshot(policy, command, cwd, env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL) as proc:
        return _collect(proc, timeout)


@contextlib.contextmanager
def _oneshot(policy: Policy, command: Sequence[str], cwd: str, env: Dict[str, str],
             **streams) -> Iterator[subprocess.Popen]:
    """A oneshot sandbox's process, in a pids cgroup of its own where the machine gives one;
    at the end every process it started is killed."""
    group = PidsCgroup.create(policy.limits.processes)
    argv = (group.join_prefix() if group is not None else []) + commands.oneshot_command(
        policy, command, cwd, traverser(*identity(policy.level, policy.user)), counted=group is not None)
    proc = subprocess.Popen(argv, cwd=cwd, env=env, stdin=subprocess.DEVNULL, start_new_session=True, **streams)
    try:
        yield proc
    finally:
        procs.signal_all(procs.descendants(proc.pid) + [proc.pid], signal.SIGKILL)
        proc.wait()
        if group is not None:
            group.remove_when_empty(KEEPER_EXIT_S)


def end_user_processes(user: str, gid: int, rounds: int = 20) -> int:
    """Kill every process of `user` (the sandbox user) whose real group is `gid` (one grading's:
    policy.grading_gid), frozen first each round; how many. Where no PID namespace holds a run's
    processes (isolation `user only`), a helper that left its session and emptied its environment
    escapes the run's own sweep: the grader calls this once every run is over. The group keeps
    the sweep to this grading: another grading on the machine runs as the same user."""
    uid = pwd.getpwnam(user).pw_uid
    killed = set()
    for _ in range(rounds):
        pids = [pid for pid in procs.local_pids()  # a container's gradings number their groups apart
                if procs.owner(pid) == uid and procs.real_group(pid) == gid and pid != os.getpid()]
        if not pids:
            break
        for sig in (signal.SIGSTOP, signal.SIGKILL):
            procs.signal_all(pids, sig)
        killed.update(pids)
    return len(killed)
