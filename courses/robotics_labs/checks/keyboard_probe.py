"""Typing keys into a student's keyboard node and finding its key map.

discover_keymap() types keys into the node's terminal (keymap.KeyMapSearch decides which) and
watches its velocity commands; with a Motion, each key found must also move the robot that way
(one press per direction in all: the simulated Burger bucks when its commands reverse too often).
The node itself is started by course_milestones.students (start_registering, Roslaunch). A helper
of the built-in course's keyboard checks (teleop, checkpoint2, launch_params, turtlebot): `import
keyboard_probe as kp`.
"""
from __future__ import annotations

import math
import time
from typing import Callable, List, NamedTuple, Optional, Sequence, Tuple

import rosgraph
import rospy

from course_format import causes
from course_milestones.discovery import CALLER, node_uris, published_type, sends_to
from course_milestones.students import RAW_WAIT, wait_for_publisher
from course_checks.artifacts import artifact_path
from course_checks.keyboard import PtyKeyboard
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

import keymap as km  # beside it in the course's checks/

PROBE_WINDOW = 1.5        # s: how long a key press has to produce its command
PUBLISHER_SIDE_WAIT = 3.0  # s: how long wait_connected waits for the node to list our connection
# s: how long a node started again has to publish again: as long as its first start had (a launch
# file's restart starts its simulator too; under a class's grading load it took over 15 s once)
RESTART_TIMEOUT = 30.0
Pose = Tuple[float, float, float]


def wait_connected(recorder: TopicRecorder, node: Optional[str] = None, timeout: float = 10.0) -> bool:
    """Our subscriber is connected to `node`'s publisher (any publisher if None), so a command it
    publishes now reaches us. A connection to a node that just died can linger: naming the node
    waits for the new one. With `node`, this also waits (up to PUBLISHER_SIDE_WAIT) until the
    node itself lists the connection (discovery.sends_to): before that, a command it publishes
    is lost, and a key press typed then looks unanswered. That second wait never fails the
    check: a node whose bus info says nothing only costs the wait."""
    try:
        uri = rosgraph.Master(CALLER).lookupNode(node) if node else None
    except rosgraph.MasterException:
        return False
    if uri is not None and wrong_type(recorder, uri):
        return False  # it can never connect: the check says why (wrong_type)

    def connected():
        return any(uri is None or c.endpoint_id == uri for c in recorder.sub.impl.connections)
    if not wait_for(connected, timeout):
        return False
    if uri is not None:
        me, topic = rospy.get_caller_id(), recorder.sub.resolved_name
        wait_for(lambda: sends_to(uri, topic, me) is not False, PUBLISHER_SIDE_WAIT)
    return True


def connect(recorder: TopicRecorder, node: str) -> Optional[str]:
    """wait_connected, as a check's failure: None once connected, else why not (the node publishes
    the topic with another type: wrong_type; else silent)."""
    if wait_connected(recorder, node):
        return None
    return type_problem(recorder, node) or causes.finding("silent", "could not subscribe to %s"
                                                          % recorder.sub.resolved_name)


def wrong_type(recorder: TopicRecorder, node_uri: str) -> Optional[str]:
    """The type the node publishes the recorder's topic with, when it is not the recorder's (a
    Twist subscriber never connects to an Empty publisher: no key would ever be answered)."""
    sent = published_type(node_uri, recorder.sub.resolved_name)
    wanted = recorder.sub.data_class._type
    return sent if sent and sent != wanted else None


def type_problem(recorder: TopicRecorder, node: str) -> Optional[str]:
    """A sentence (cause wrong_type) when `node` publishes the recorder's topic with another type."""
    try:
        sent = wrong_type(recorder, rosgraph.Master(CALLER).lookupNode(node))
    except rosgraph.MasterException:
        return None
    if not sent:
        return None
    return causes.finding("wrong_type", "%s publishes %s as %s; it must carry %s, the type the robot's simulator "
                          "subscribes with, or no command reaches it" % (node, recorder.sub.resolved_name, sent,
                                                                         recorder.sub.data_class._type))


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
    result and the first failure as a sentence carrying its cause (a causes.Finding; None if every
    direction has a key that moves the robot)."""
    started = time.monotonic()
    keyboard.raw_wait = keyboard.raw_wait or RAW_WAIT
    trace: List[str] = []
    result, problem = _search(keyboard, commands, km.KeyMapSearch(first=first), motion, window, trace)
    report_keymap(result, who, time.monotonic() - started, trace)
    return result, problem


def _search(keyboard, commands, search, motion, window, trace):
    pressed: List[km.Probe] = []  # since the node (re)started
    started = time.monotonic()
    while True:
        if search.restart_due:
            trace.append("%5.2f s: started again (it exited)" % (time.monotonic() - started))
            problem = _restart(keyboard, commands, "after it exited on %s"
                               % km.key_label(search.exited_on[-1].key, search.exited_on[-1].enter))
            if problem:
                return search.result(), problem
            search.restarted()
            pressed = []
        probe = search.next_probe()
        if (probe is not None and keyboard.seen_raw and not search.arrows_answered
                and km.stale_bytes_risk(pressed, probe)):
            trace.append("%5.2f s: started again (a letter key after an unanswered arrow)" % (time.monotonic() - started))
            problem = _restart(keyboard, commands, "to try letter keys after the arrows")
            if problem:
                return search.result(), problem
            pressed = []
        if probe is None:
            result = search.result()
            return result, km.failure_message(result, commands.sub.resolved_name, motion.subject if motion else "it")
        if not search.suits(probe, keyboard.seen_raw):
            search.skip()  # the node reads single keys (its terminal was seen in raw mode), or lines: not both
            continue
        mark = commands.count
        before = motion.pose() if motion else None
        pressed_at = time.monotonic()
        keyboard.press(probe.key, probe.enter)
        typed_at = time.monotonic()
        raw = keyboard.raw_mode()
        pressed.append(probe)
        wanted = search.wanted()

        def answered():
            return any(km.answers(d, m.linear.x, m.angular.z) for m in commands.messages[mark:] for d in wanted)
        wait_for(lambda: answered() or not keyboard.node.running(), window)
        seen = tuple(km.Command.of(m) for m in commands.messages[mark:])
        outcome = km.Outcome(seen, exited=not keyboard.node.running())
        gave = search.record(probe, outcome)
        trace.append(press_line(probe, outcome, pressed_at - started, typed_at - pressed_at, raw,
                                time.monotonic() - typed_at))
        for direction in gave if motion is not None else ():
            problem = _check_moved(keyboard, probe, direction, before, motion)
            if problem:
                return search.result(), problem


def _restart(keyboard: PtyKeyboard, commands: TopicRecorder, why: str) -> Optional[str]:
    """Start the node afresh (see keymap.stale_bytes_risk; or it exited on a key) and wait until it
    publishes to us again (same node name, new URI)."""
    topic = commands.sub.resolved_name
    before = node_uris()
    keyboard.restart()
    fresh = wait_for_publisher(topic, keyboard, RESTART_TIMEOUT, before)
    if fresh is None or not wait_connected(commands, fresh.node):
        return causes.finding("not_published", "started again %s, it did not publish %s again" % (why, topic))
    return None


def _check_moved(keyboard: PtyKeyboard, probe: km.Probe, direction: str, before: Optional[Pose],
                 motion: Motion) -> Optional[str]:
    if before is None:
        return causes.finding("course_tools", "no pose of %s to check its motion" % motion.subject)

    def went():
        return km.moved(direction, before, motion.pose(), motion.min_distance, motion.min_angle)
    if wait_for(went, motion.interval) or keyboard.press_until(probe.key, went, motion.tries, motion.interval,
                                                                probe.enter):
        return None
    return causes.finding("not_moving", "after pressing %s, %s did not %s (pose x=%.2f y=%.2f theta=%.2f -> x=%.2f "
                          "y=%.2f theta=%.2f)" % (km.key_label(probe.key, probe.enter), motion.subject,
                                                  km.WORDS[direction], *before, *motion.pose()))


def press_line(probe: km.Probe, outcome: km.Outcome, at: float, typing: float, raw: bool, after: float) -> str:
    """One press for the artifact: when, the key, whether the terminal was in raw mode once it
    was typed, and what came back (commands seen within the window, or none)."""
    seen = ", ".join(c.describe() for c in outcome.commands[:3]) or "no command"
    return "%5.2f s: %s typed after %.2f s, terminal %s -> %s%s in %.2f s" % (
        at, km.key_label(probe.key, probe.enter), typing, "raw" if raw else "line by line", seen,
        " (the node exited)" if outcome.exited else "", after)


def report_keymap(result: km.SearchResult, who: str, seconds: float, trace: Sequence[str] = ()) -> str:
    """Print (test output) and save (artifacts) the key map found, with each press after it in
    the artifact; the line printed."""
    line = "key map of %s: %s (%d key presses, %.1f s)" % (
        who, result.keymap.describe() if result.keymap else "none found", result.presses, seconds)
    print(line, flush=True)
    with open(artifact_path("keymap"), "w") as out:
        out.write("".join(text + "\n" for text in [line, *trace]))
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
