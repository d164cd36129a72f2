"""The ROS and terminal side of finding a keyboard controller and its key map.

- start_registering(): start a package's executables one by one (each on its own
  pseudo-terminal) until one registers what the text asks (e.g. a publisher on /turtle1/cmd_vel);
  the text names the package, not the script.
- discover_keymap(): type keys into the node's terminal (KeyMapSearch decides which) and watch
  its velocity commands; with a Motion, each key found must also move the robot that way (one
  press per direction in all: the simulated Burger bucks when its commands reverse too often).
"""
from __future__ import annotations

import math
import os
import re
import shutil
import time
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence, Tuple

import rosgraph

from course_milestones import keymap as km
from course_milestones.discovery import Registration, describe, list_executables, system_state
from course_testkit.artifacts import artifact_path
from course_testkit.keyboard import PtyKeyboard
from course_testkit.recorders import TopicRecorder
from course_testkit.waiting import wait_for

PROBE_WINDOW = 1.5        # s: how long a key press has to produce its command
REGISTER_TIMEOUT = 15.0   # s: how long an executable has to register what is asked
RAW_WAIT = 1.0            # s: how long a key waits for the node's terminal to be in raw mode
SETTLED = 3.0             # s: a node registered for this long with other topics is not the one asked for
Pose = Tuple[float, float, float]


class Started(NamedTuple):
    """The executable that registered what was asked, its process and its registration."""

    path: str
    keyboard: PtyKeyboard
    registration: Registration


def _hinted_first(paths: Sequence[str], hint: str) -> List[str]:
    pattern = re.compile(hint, re.IGNORECASE)
    return sorted(paths, key=lambda p: (not pattern.search(os.path.basename(p)), os.path.basename(p)))


def _topics(reg: Registration) -> Tuple[str, ...]:
    return tuple(t for t in reg.publishes + reg.subscribes + reg.services
                 if t != "/rosout" and not t.endswith(("/get_loggers", "/set_logger_level")))


def node_uris() -> Dict[str, str]:
    """Every registered node's name -> XML-RPC URI. A node started under a name already taken
    replaces the old one: the name stays, the URI changes, so new nodes are told apart by URI."""
    master = rosgraph.Master("/course_milestone")
    uris = {}
    for node in system_state():
        try:
            uris[node] = master.lookupNode(node)
        except rosgraph.MasterException:
            pass
    return uris


def new_registrations(before: Dict[str, str]) -> List[Registration]:
    """Registrations of nodes that were not in `before` (name -> URI), or are there under a new URI."""
    uris = node_uris()
    return [reg for name, reg in system_state().items() if name in uris and before.get(name) != uris[name]]


def start_registering(pkg: str, args: Sequence[str], wanted: Callable[[Registration], bool], hint: str = "",
                      log_name: str = "node", timeout: float = REGISTER_TIMEOUT,
                      ) -> Tuple[Optional[Started], List[str]]:
    """Start each executable of `pkg` with `args`, on a pseudo-terminal, until one registers a node
    that satisfies `wanted`; executables whose name matches `hint` go first. Returns it (still
    running) and, for the failure message, what each other executable did."""
    tried: List[str] = []
    for path in _hinted_first(list_executables(pkg), hint):
        keyboard, found, seen = start_and_wait([path] + list(args), wanted, log_name, timeout)
        if found is not None:
            return Started(path, keyboard, found), tried
        keyboard.stop()
        tried.append(describe_attempt(os.path.basename(path), keyboard, seen))
    return None, tried


def start_and_wait(command: Sequence[str], wanted: Callable[[Registration], bool], log_name: str,
                   timeout: float = REGISTER_TIMEOUT, env: Optional[Dict[str, str]] = None,
                   ) -> Tuple[PtyKeyboard, Optional[Registration], List[Registration]]:
    """Start one node on a pseudo-terminal and wait until it registers what `wanted` asks; gives up
    when it exits, after `timeout`, or once it has stayed registered for SETTLED seconds without
    it. Returns the keyboard (still running), the registration (or None) and what it registered."""
    before = node_uris()
    keyboard = PtyKeyboard(command, log_path=artifact_path(log_name), env=env)
    deadline = time.monotonic() + timeout
    first_seen: Optional[float] = None
    while True:
        seen = new_registrations(before)
        for reg in seen:
            if wanted(reg):
                return keyboard, reg, seen
        now = time.monotonic()
        if seen and first_seen is None:
            first_seen = now
        settled = first_seen is not None and now - first_seen > SETTLED
        if now > deadline or settled or not keyboard.node.running():
            return keyboard, None, seen
        time.sleep(0.1)


def describe_attempt(name: str, keyboard: PtyKeyboard, seen: Sequence[Registration]) -> str:
    """What a started executable did instead of what was asked, for a failure message."""
    if seen:
        return "%s registered %s (%s)" % (name, ", ".join(r.node for r in seen),
                                          ", ".join(sorted({t for r in seen for t in _topics(r)})) or "no topics")
    if not keyboard.node.running():
        return "%s exited with status %s" % (name, keyboard.node.proc.returncode)
    return "%s registered no node" % name


def publishes(topic: str) -> Callable[[Registration], bool]:
    return lambda reg: topic in reg.publishes


def subscribes(topic: str) -> Callable[[Registration], bool]:
    return lambda reg: topic in reg.subscribes


def wait_connected(recorder: TopicRecorder, node: Optional[str] = None, timeout: float = 10.0) -> bool:
    """Our subscriber is connected to `node`'s publisher (any publisher if None), so a command it
    publishes now reaches us. A connection to a node that just died can linger: naming the node
    waits for the new one."""
    try:
        uri = rosgraph.Master("/course_milestone").lookupNode(node) if node else None
    except rosgraph.MasterException:
        return False

    def connected():
        return any(uri is None or c.endpoint_id == uri for c in recorder.sub.impl.connections)
    return bool(wait_for(connected, timeout))


class Motion(NamedTuple):
    """How to see that a key press moved the robot: its pose (x, y, theta), what to call it in
    messages, the smallest move that counts, and how often to press again while it has not moved
    (turtlesim's or the simulator's connection to a new node can trail ours)."""

    pose: Callable[[], Optional[Pose]]
    subject: str
    min_distance: float
    min_angle: float
    interval: float = 2.0
    tries: int = 5


def discover_keymap(keyboard: PtyKeyboard, commands: TopicRecorder, who: str, first: Optional[km.KeyMap] = None,
                    motion: Optional[Motion] = None, window: float = PROBE_WINDOW,
                    ) -> Tuple[km.SearchResult, Optional[str]]:
    """Type keys into `keyboard` until the search has a key for each direction (or none is left),
    judging each press by the Twists `commands` records after it. With `motion`, each key found
    must also move the robot that way. Reports the key map found as `who`'s; returns the search
    result and the first failure as a sentence (None if every direction has a key that moves the robot)."""
    started = time.monotonic()
    keyboard.raw_wait = keyboard.raw_wait or RAW_WAIT
    result, problem = _search(keyboard, commands, km.KeyMapSearch(first=first), motion, window)
    report_keymap(result, who, time.monotonic() - started)
    return result, problem


def _search(keyboard, commands, search, motion, window):
    pressed: List[km.Probe] = []  # since the node (re)started
    while True:
        probe = search.next_probe()
        if probe is not None and search.keymap is None and keyboard.seen_raw and km.stale_bytes_risk(pressed, probe):
            problem = _restart(keyboard, commands)
            if problem:
                return search.result(), problem
            pressed = []
        if probe is None:
            result = search.result()
            return result, km.failure_message(result, commands.sub.resolved_name, motion.subject if motion else "it")
        if probe.enter and keyboard.seen_raw:
            search.skip()  # the node reads single keys (its terminal was seen in raw mode): no Enter
            continue
        mark = commands.count
        before = motion.pose() if motion else None
        keyboard.press(probe.key, probe.enter)
        pressed.append(probe)

        def answered():
            return any(km.answers(probe.direction, m.linear.x, m.angular.z) for m in commands.messages[mark:])
        wait_for(lambda: answered() or not keyboard.node.running(), window)
        seen = tuple((m.linear.x, m.angular.z) for m in commands.messages[mark:])
        outcome = km.Outcome(seen, exited=not keyboard.node.running())
        search.record(probe, outcome)
        if motion is not None and outcome.answered(probe.direction):
            problem = _check_moved(keyboard, probe, before, motion)
            if problem:
                return search.result(), problem


def _restart(keyboard: PtyKeyboard, commands: TopicRecorder) -> Optional[str]:
    """Start the node afresh (see keymap.stale_bytes_risk) and wait until it publishes to us again
    (same node name, new URI)."""
    topic = commands.sub.resolved_name
    before = node_uris()
    keyboard.restart()
    fresh = wait_for_publisher(topic, keyboard, REGISTER_TIMEOUT, before)
    if fresh is None or not wait_connected(commands, fresh.node):
        return "started again to try letter keys after the arrows, it did not publish %s again" % topic
    return None


def _check_moved(keyboard: PtyKeyboard, probe: km.Probe, before: Optional[Pose], motion: Motion) -> Optional[str]:
    if before is None:
        return "no pose of %s to check its motion" % motion.subject

    def went():
        return km.moved(probe.direction, before, motion.pose(), motion.min_distance, motion.min_angle)
    if wait_for(went, motion.interval) or keyboard.press_until(probe.key, went, motion.tries, motion.interval,
                                                                probe.enter):
        return None
    return ("after pressing %s, %s did not %s (pose x=%.2f y=%.2f theta=%.2f -> x=%.2f y=%.2f theta=%.2f)"
            % (km.key_label(probe.key, probe.enter), motion.subject, km.WORDS[probe.direction], *before,
               *motion.pose()))


def report_keymap(result: km.SearchResult, who: str, seconds: float) -> str:
    """Print (test output) and save (artifacts) the key map found; the line printed."""
    line = "key map of %s: %s (%d key presses, %.1f s)" % (
        who, result.keymap.describe() if result.keymap else "none found", result.presses, seconds)
    print(line, flush=True)
    with open(artifact_path("keymap"), "w") as out:
        out.write(line + "\n")
    return line


def turtle_pose(recorder: TopicRecorder) -> Callable[[], Optional[Pose]]:
    """turtlesim/Pose recorder -> (x, y, theta) of the newest pose."""
    def pose():
        last = recorder.last
        return None if last is None else (last.x, last.y, last.theta)
    return pose


def odom_pose(recorder: TopicRecorder) -> Callable[[], Optional[Pose]]:
    """nav_msgs/Odometry recorder -> (x, y, yaw) of the newest odometry."""
    def pose():
        last = recorder.last
        if last is None:
            return None
        p, q = last.pose.pose.position, last.pose.pose.orientation
        return p.x, p.y, math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
    return pose


def not_found_message(pkg: str, what: str, tried: Sequence[str]) -> str:
    executables = list_executables(pkg)
    if not executables:
        return "package %s has no executable script (is it chmod +x, in scripts/ or nodes/?)" % pkg
    return "no executable in package %s %s (found: %s; %s)" % (pkg, what, describe(executables), "; ".join(tried))


def launch_in_terminal(pkg: str, launch_file: str, log_name: str) -> PtyKeyboard:
    """`roslaunch PKG FILE`, exactly as the text types it, with a pseudo-terminal as its keyboard
    (roslaunch's nodes share its terminal, as in the student's own shell)."""
    return PtyKeyboard([shutil.which("roslaunch") or "roslaunch", pkg, launch_file], log_path=artifact_path(log_name))


def wait_for_publisher(topic: str, keyboard: PtyKeyboard, timeout: float = 30.0,
                       before: Optional[Dict[str, str]] = None) -> Optional[Registration]:
    """The first node (not in `before`, name -> URI) that publishes `topic`, while `keyboard`'s
    process runs; None after `timeout`."""
    before = before or {}
    found = wait_for(lambda: [r for r in new_registrations(before) if topic in r.publishes]
                     or not keyboard.node.running(), timeout)
    return found[0] if isinstance(found, list) and found else None
