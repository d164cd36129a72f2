"""A student's executables and launch files as processes we own: start them, see which of them
registered what (the text names the package, not the scripts), describe what each did for a
failure message, and stop them. Every process runs in its own process group, with its output in
an artifact log (course_checks.artifacts) that the grader shows the student.

When the grader runs the check, every student process goes into the run's sandbox
(course_sandbox: its own namespaces, read-only course, hidden outputs, an unprivileged user,
limits), named by $COURSE_SANDBOX_POLICY; `run_sandbox()` is that sandbox, None under a plain
`rostest`. The simulators and the check itself stay outside.

Three ways of starting a student's code, for three kinds of node:
- Script: with a pipe as stdin, several at once, each registered node tied to the process that
  started it by the node's pid (XML-RPC getPid): the text's publisher, subscriber or server is
  whichever script registers it (find_role). Lines can be typed on the pipe (input()).
- Registered: one at a time on a pseudo-terminal (a keyboard, for nodes reading keys), until one
  registers what is asked (start_registering); new nodes are told apart by their URI.
- Roslaunch: `roslaunch PKG FILE` as the text types it, on a pseudo-terminal that every node it
  starts inherits (a keyboard node in the launch file gets a terminal to read).
"""
from __future__ import annotations

import atexit
import functools
import os
import re
import signal
import subprocess
import time
import xmlrpc.client
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence, Tuple, Union

from course_sandbox import policy as sandbox_policy
from course_sandbox.run import RunSandbox

import rospkg

from course_format import causes
from course_milestones import master_log
from course_milestones.discovery import (CALLER, Registration, describe as describe_names, list_executables,
                                         new_registrations, node_uris, own_names, package_dir,
                                         registrations_with_uris)
from course_milestones.scripts import output_problems, script_problems
from course_checks.artifacts import artifact_path
from course_checks.keyboard import PtyKeyboard
from course_checks.nodes import NodeProcess
from course_checks.waiting import wait_for

# What rospy prints when the master stops a node because a newer one took its name.
SAME_NAME = "new node registered with same name"
REGISTER_TIMEOUT = 15.0   # s: how long an executable on a terminal has to register what is asked
RAW_WAIT = 1.0            # s: how long a key waits for the node's terminal to be in raw mode (PtyKeyboard.raw_wait)
SETTLED = 3.0             # s: a node registered for this long with other topics is not the one asked for
# Why a node that subscribed no longer does, while it still runs.
ONE_MESSAGE = ("a node that takes one message (e.g. rospy.wait_for_message, ros::topic::waitForMessage) stops "
               "listening after it; keep a subscriber and spin")
# roslaunch escalates SIGINT -> SIGTERM -> SIGKILL on its nodes within ~17 s; stop it within that.
ROSLAUNCH_STOP_S = 25.0


@functools.lru_cache(maxsize=1)
def run_sandbox() -> Optional[RunSandbox]:
    """The sandbox of this milestone run (one per check process), or None without a policy. Its
    processes all end when the check exits."""
    policy = sandbox_policy.from_environment()
    if policy is None:
        return None
    sandbox = RunSandbox(policy)
    atexit.register(sandbox.close)
    return sandbox


def run_captured(argv: Sequence[str], timeout: float = 30.0) -> Tuple[Optional[int], bytes]:
    """Run a command as student code (in the run's sandbox when there is one) to its end: its
    exit code (None past `timeout`) and its standard output, at most 1 MiB."""
    sandbox = run_sandbox()
    if sandbox is not None:
        return sandbox.run_captured(argv, timeout)
    from course_sandbox.run import _collect
    proc = subprocess.Popen(list(argv), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    return _collect(proc, timeout)


class Script(NamedTuple):
    """One student executable started with a pipe as stdin; its output is node.output()."""

    path: str
    node: NodeProcess

    @property
    def name(self) -> str:
        return os.path.basename(self.path)


def start(path: str, args: Sequence[str] = ()) -> Script:
    """Start one executable with a pipe as stdin (for typed lines) and its output in an artifact log."""
    log = artifact_path(os.path.basename(path))
    return Script(path, NodeProcess([path] + list(args), stdin=subprocess.PIPE, log_path=log, sandbox=run_sandbox()))


def stop_all(started: Sequence[Script]) -> None:
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


def end_all(started: Sequence[Script]) -> None:
    """A check's clean-up once its verdict is in: every started executable killed at once
    (NodeProcess.end), without the Ctrl+C of stop_all."""
    for s in started:
        s.node.end()


def registrations_of(started: Script, known: Dict[str, int]) -> List[Registration]:
    """What the nodes this process (or its children) registered, per node; `known` caches
    node URI -> process group."""
    regs = []
    for reg, uri in registrations_with_uris():
        if uri not in known:  # by URI: a node started under a name already taken replaces the old one
            known[uri] = _process_group(uri)
        if known[uri] == started.node.proc.pid:
            regs.append(reg)
    return regs


def _process_group(uri: str) -> int:
    try:
        _, _, pid = xmlrpc.client.ServerProxy(uri).getPid(CALLER)
        sandbox = run_sandbox()
        host_pid = sandbox.host_pid(pid) if sandbox is not None else pid  # getPid answers the sandbox's pid
        return os.getpgid(host_pid) if host_pid is not None else -1
    except Exception:  # noqa: BLE001 - the node went away, or is not on this machine
        return -1


def find_role(started: Sequence[Script], condition: Callable[[Registration], bool], timeout: float,
              known: Dict[str, int], settle: Optional[float] = None) -> Optional[Script]:
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


def describe(started: Sequence[Script], known: Dict[str, int]) -> str:
    """What each started executable did, for a failure message: 'a.py publishes /x; b.py exited (code 1)'."""
    return "; ".join("%s %s" % (s.name, did(s, known)) for s in started) or "(no executables)"


def did(started: Script, known: Dict[str, int]) -> str:
    """What one started executable did, its name left out: 'offers /turtle1/patrol', 'exited (code 1)...'."""
    regs = registrations_of(started, known)
    if not started.node.running() and not regs:
        return "exited (code %s)%s" % (started.node.proc.returncode, last_words(started))
    words = []
    for kind in ("publishes", "subscribes", "services"):
        names = sorted({n for r in regs for n in own_names(getattr(r, kind))})
        if names:
            words.append("%s %s" % ("offers" if kind == "services" else kind, ", ".join(names)))
    return " and ".join(words) if words else "registered nothing"


def role_missing(text: str, started: Sequence[Script], known: Dict[str, int], kind: str,
                 pkg: str = "") -> causes.Finding:
    """`text`, the failure when no started executable registered the topic asked for, carrying the
    cause wrong_topic when one did register a topic of its own of that `kind` (publishes,
    subscribes): the code is there, on another name than the text's; else why they did not start
    (start_cause: `pkg`'s scripts, what the started ones printed), else not_started."""
    other = any(own_names(getattr(r, kind)) for s in started for r in registrations_of(s, known))
    if other:
        return causes.finding("wrong_topic", text)
    return causes.finding(start_cause(pkg, [output_of(s.node) for s in started]), text)


def start_cause(pkg: str, outputs: Sequence[str] = (), default: str = "not_started") -> str:
    """Why the student's executables did not do what was asked, where their files or output say it:
    the cause of the first script of `pkg` that rosrun cannot start or Python 3 cannot compile
    (course_milestones.scripts.script_problems), else of the first mistake `outputs` (what they
    printed) show (scripts.output_problems: Python 2 met at run time); else `default`."""
    try:
        problems = script_problems(package_dir(pkg)) if pkg else []
    except rospkg.ResourceNotFound:
        problems = []
    problems += [p for output in outputs for p in output_problems(output)]
    return causes.of(problems[0], default) if problems else default


def output_of(node: NodeProcess) -> str:
    """What a started process (a Script's or a PtyKeyboard's node) printed so far ("" when its log
    cannot be read)."""
    try:
        return node.output()
    except OSError:
        return ""


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


def last_words(started: Union[Script, PtyKeyboard]) -> str:
    """The end of a process's output, for a failure message (with a hint when rospy stopped it
    because another node took its name)."""
    try:
        tail = started.node.output().strip()[-200:]
    except OSError:
        return ""
    if not tail:
        return ""
    hint = ""
    if SAME_NAME in tail:
        hint = (" (another node took its name: give each node its own name, e.g. from its argument, "
                "or rospy.init_node(..., anonymous=True))")
    return ", its output ending with %r%s" % (tail, hint)


class Registered(NamedTuple):
    """The executable that registered what was asked, running on a pseudo-terminal, and its registration."""

    path: str
    keyboard: PtyKeyboard
    registration: Registration


def hinted_first(paths: Sequence[str], hint: str) -> List[str]:
    """`paths` sorted by name, those whose name matches the regex `hint` first (only the order of trying)."""
    pattern = re.compile(hint, re.IGNORECASE)
    return sorted(paths, key=lambda p: (not pattern.search(os.path.basename(p)), os.path.basename(p)))


def start_registering(pkg: str, args: Sequence[str], wanted: Callable[[Registration], bool], hint: str = "",
                      log_name: str = "node", timeout: float = REGISTER_TIMEOUT, keep_exited: bool = False,
                      ) -> Tuple[Optional[Registered], List[str]]:
    """Start each executable of `pkg` with `args`, on a pseudo-terminal, until one registers a node
    that satisfies `wanted`; executables whose name matches `hint` go first. Returns it (still
    running) and, for the failure message, what each other executable did. With `keep_exited`, one
    that registered it (the master's log says so) and exited before it was seen is returned too,
    exited, as if it had been seen before it exited: when it exits is then no matter of timing."""
    tried: List[str] = []
    history = master_log.History()
    for path in hinted_first(list_executables(pkg), hint):
        before = set(node_uris())
        history.mark()
        keyboard, found, seen = start_and_wait([path] + list(args), wanted, log_name, timeout)
        if found is not None:
            return Registered(path, keyboard, found), tried
        earlier = [r for node, r in master_log.ever_registered(history.since()).items() if node not in before]
        did = [r for r in earlier if wanted(r)]
        if keep_exited and did and not keyboard.node.running():
            return Registered(path, keyboard, did[0]), tried
        tried.append(describe_attempt(os.path.basename(path), keyboard, seen, earlier, wanted))
        keyboard.stop()
    return None, tried


def start_and_wait(command: Sequence[str], wanted: Callable[[Registration], bool], log_name: str,
                   timeout: float = REGISTER_TIMEOUT, env: Optional[Dict[str, str]] = None,
                   ) -> Tuple[PtyKeyboard, Optional[Registration], List[Registration]]:
    """Start one node on a pseudo-terminal and wait until it registers what `wanted` asks; gives up
    when it exits, after `timeout`, or once it has stayed registered for SETTLED seconds without
    it. Returns the keyboard (still running), the registration (or None) and what it registered."""
    before = node_uris()
    keyboard = PtyKeyboard(command, log_path=artifact_path(log_name), env=env, sandbox=run_sandbox())
    found, seen = wait_registering(keyboard, before, wanted, timeout)
    return keyboard, found, seen


def wait_registering(process: PtyKeyboard, before: Dict[str, str], wanted: Callable[[Registration], bool],
                     timeout: float = REGISTER_TIMEOUT, settle: float = SETTLED,
                     ) -> Tuple[Optional[Registration], List[Registration]]:
    """Wait until a node registered since `before` (name -> URI) satisfies `wanted`, while
    `process` (a node, or roslaunch) runs; gives up after `timeout`, or once new nodes have been
    registered for `settle` seconds without it. The registration (or None) and every new one."""
    deadline = time.monotonic() + timeout
    first_seen: Optional[float] = None
    while True:
        seen = new_registrations(before)
        for reg in seen:
            if wanted(reg):
                return reg, seen
        now = time.monotonic()
        if seen and first_seen is None:
            first_seen = now
        settled = first_seen is not None and now - first_seen > settle
        if now > deadline or settled or not process.node.running():
            return None, seen
        time.sleep(0.1)


class Attempt(str):
    """What a started executable did, in words; `left`: it did register what was asked, then
    stopped (the cause to tell first: the rest of a failure message follows from it), and how
    (`cause`, a causes key)."""
    left = False
    cause = ""


def _left(text: str, cause: str) -> Attempt:
    attempt = Attempt(text)
    attempt.left = True
    attempt.cause = cause
    return attempt


def describe_attempt(name: str, keyboard: PtyKeyboard, seen: Sequence[Registration],
                     earlier: Sequence[Registration] = (), wanted: Optional[Callable[[Registration], bool]] = None,
                     ) -> str:
    """What a started executable did instead of what was asked, for a failure message: what it
    registered, and, when the master's log shows it did register what was asked (`earlier`)
    but no longer does, that it left it, and how (still running, or its exit status and last
    output)."""
    running = keyboard.node.running()
    ended = "exited with status %s%s" % (keyboard.node.proc.returncode, last_words(keyboard))
    did = [r for r in earlier if wanted is not None and wanted(r)]
    if did and not any(wanted(r) for r in seen):
        what = "%s (node %s)" % (registered_words(did[0]), did[0].node)
        if running:
            stopped = "stopped listening" if own_names(did[0].subscribes) \
                and not own_names(did[0].publishes + did[0].services) else "unregistered it"
            return _left("%s %s, then %s while still running: %s" % (name, what, stopped, ONE_MESSAGE),
                         "stopped_listening" if stopped == "stopped listening" else "unregistered")
        # registering what was asked is not yet doing it: the check never saw it work (no spin)
        return _left("%s %s, then %s" % (name, what, ended), causes.exited(False))
    if seen:
        names = sorted({n for r in seen for n in own_names(r.publishes + r.subscribes + r.services)})
        words = "%s registered %s (%s)" % (name, ", ".join(r.node for r in seen), ", ".join(names) or "no topics")
        return words if running else _printed("%s, then %s" % (words, ended), keyboard)
    if not running:
        return _printed("%s %s" % (name, ended), keyboard)
    return "%s registered no node" % name


def _printed(text: str, keyboard: PtyKeyboard) -> Attempt:
    """`text`, what an executable that exited did, carrying the cause of the first mistake its
    output shows (scripts.output_problems), if any."""
    attempt = Attempt(text)
    attempt.cause = start_cause("", [output_of(keyboard.node)], "")
    return attempt


def registered_words(reg: Registration) -> str:
    """'subscribed /turtle1/pose and published /x' for what a node registered (rospy's routine names left out)."""
    parts = []
    for verb, names in (("published", reg.publishes), ("subscribed", reg.subscribes), ("offered", reg.services)):
        own = own_names(names)
        if own:
            parts.append("%s %s" % (verb, ", ".join(own)))
    return " and ".join(parts) or "registered nothing of its own"


def not_found_message(pkg: str, what: str, tried: Sequence[str]) -> causes.Finding:
    """The failure when no executable of `pkg` registered `what` (with what each one did instead),
    carrying its cause: that of an executable that did it and then stopped, else why they did not
    start (start_cause: `pkg`'s scripts, then the first cause an attempt's output showed), else
    not_started."""
    executables = list_executables(pkg)
    if not executables:
        return causes.finding(start_cause(pkg), "package %s has no executable script (is it chmod +x? it may be "
                                                "anywhere in the package but its test folders)" % pkg)
    left = [t for t in tried if getattr(t, "left", False)]
    if left:  # it did what was asked, then stopped: that is the cause, said first
        others = [t for t in tried if t not in left]
        return causes.finding(left[0].cause, "%s; so no executable in package %s %s any more (found: %s%s)" % (
            "; ".join(left), pkg, what, describe_names(executables), "".join("; " + t for t in others)))
    printed = next((t.cause for t in tried if getattr(t, "cause", "")), "not_started")
    return causes.finding(start_cause(pkg, default=printed), "no executable in package %s %s (found: %s; %s)" % (
        pkg, what, describe_names(executables), "; ".join(tried)))


def wait_for_publisher(topic: str, keyboard: PtyKeyboard, timeout: float = 30.0,
                       before: Optional[Dict[str, str]] = None) -> Optional[Registration]:
    """The first node (not in `before`, name -> URI) that publishes `topic`, while `keyboard`'s
    process runs; None after `timeout`."""
    before = before or {}
    found = wait_for(lambda: [r for r in new_registrations(before) if topic in r.publishes]
                     or not keyboard.node.running(), timeout)
    return found[0] if isinstance(found, list) and found else None


class Roslaunch(PtyKeyboard):
    """`roslaunch PKG FILE ARGS...` on a pseudo-terminal, its output in the artifact `<log_name>.log`.
    roslaunch runs against the master of the milestone's rostest (ROS_MASTER_URI is inherited);
    stop() also ends the nodes it started in sessions of their own. A student's launch file runs
    in the run's sandbox; `student=False` is for the course's own (a simulator the check starts)."""

    def __init__(self, pkg: str, filename: str, log_name: str, args: Sequence[str] = (), student: bool = True) -> None:
        super().__init__(["roslaunch", pkg, filename] + list(args), log_path=artifact_path(log_name),
                         sandbox=run_sandbox() if student else None)

    def stop(self, timeout: float = ROSLAUNCH_STOP_S, grace: float = 1.5) -> Optional[int]:
        return super().stop(timeout, grace)
