"""What a data milestone's steps share while they run, one after the other: the student's processes
the `start` steps began (by their `as` name), where each one's output stood at the last action
(a `prints` step reads what came after), the turtles' poses since then (`turtle_moves`), and the
values steps saved for later ones (`call`'s `save`, named ${NAME}: course_format.saved).

A check step that fails raises StepFailed with its finding (course_format.causes); a course
file's own mistake is course_error, a failed milestone that names the step's place in the file.
"""
from __future__ import annotations

import time
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence, Set, Tuple

import rospy

from course_format import causes
from course_milestones.discovery import new_registrations, system_state
from course_checks.keyboard import PtyKeyboard
from course_checks.recorders import TopicRecorder


class StepFailed(Exception):
    """A step's failure; `finding` is the sentence (with its cause) the milestone fails with."""

    def __init__(self, finding: str) -> None:
        super().__init__(finding)
        self.finding = finding


def failed(cause: str, text: str) -> StepFailed:
    return StepFailed(causes.finding(cause, text))


def course_error(where: str, text: str) -> StepFailed:
    """A mistake in the course file itself (a bad regular expression, a type that does not exist)."""
    return failed(causes.CHECK_FAILED, "course file error at %s: %s" % (where, text))


class Started(NamedTuple):
    """A process a `start` step began: its name for later steps, the command in the text's words,
    the process (a terminal we can type on and read), the node it found (if it looked for one)
    and the nodes registered before it (a launch file's nodes are those that came after)."""

    name: str
    command: str
    process: PtyKeyboard
    node: Optional[str]
    before: Dict[str, str]
    launch: bool

    def output(self) -> str:
        try:
            return self.process.node.output()
        except OSError:
            return ""


class StepState:
    """The started processes, the marks of the last action, and the pose recorders."""

    def __init__(self, packages: Sequence[str] = (), on_action: Sequence[Callable[["StepState"], None]] = (),
                 renamed: Optional[Dict[str, str]] = None) -> None:
        """`packages`: the student's packages the milestone names; `on_action`: called as each action
        begins, before its marks are taken (to start watching what an action may change);
        `renamed`: a package the steps name -> the package run in its place."""
        self.packages = tuple(packages)
        self.renamed = dict(renamed or {})
        self.on_action = tuple(on_action)
        self.started: Dict[str, Started] = {}
        self.last: Optional[Started] = None
        # the started processes a check saw do what it asks (messages sent, a line printed): one that
        # exits afterwards did some of it (causes.exited)
        self.did: Set[str] = set()
        self.output_marks: Dict[str, int] = {}
        self.pose_recorders: Dict[str, TopicRecorder] = {}
        self.pose_marks: Dict[str, int] = {}
        self.action_time = time.monotonic()
        self.last_action = ""  # the last action in words ("`rosparam set /a 1`"), for a failure's sentence
        self.closers: List[Callable[[], None]] = []
        self.frames = None  # steps.frames.Frames, from the first TF step on
        self.saved: Dict[str, object] = {}  # what steps saved (`call`'s save), for later steps' ${NAME}

    # -- started processes ------------------------------------------------------------------------

    def add(self, started: Started) -> None:
        old = self.started.get(started.name)
        if old is not None:
            old.process.end()
        self.started[started.name] = started
        self.did.discard(started.name)
        self.last = started

    def find(self, node: Optional[str]) -> Optional[Started]:
        """The started process a step's `node` names (default: the last one started), or None."""
        if node is None or node in self.started:
            return self.last if node is None else self.started[node]
        by_node = [s for s in self.started.values() if s.node == node]
        return by_node[-1] if by_node else None

    def process(self, node: Optional[str], where: str) -> Started:
        """The started process a step's `node` names (default: the last one started)."""
        found = self.find(node)
        if found is not None:
            return found
        if node is None:
            raise course_error(where, "no `start` step before this one started a node to read")
        raise course_error(where, "node %r is not the `as` name of an earlier `start` step (%s)" % (
            node, ", ".join(self.started) or "none started"))

    def saw_working(self, node: Optional[str]) -> None:
        """A check saw the process a step's `node` names do what it asks."""
        found = self.find(node)
        if found is not None:
            self.did.add(found.name)

    def exit_cause(self, started: Started) -> str:
        """The cause of `started` having exited: whether a check saw it work before (causes.exited)."""
        return causes.exited(started.name in self.did)

    def nodes(self, node: Optional[str], where: str) -> Optional[Tuple[str, ...]]:
        """The node names a step's `node` stands for; None (any node) when no `start` step ran and
        none is named."""
        if node is not None and node.startswith("/") and node not in self.started:
            return (node,)
        if node is None and self.last is None:
            return None
        return self.nodes_of(self.process(node, where))

    def nodes_of(self, started: Started) -> Tuple[str, ...]:
        """The node a rosrun found, or every node registered since a launch file started (but those
        of processes started after it)."""
        if not started.launch and started.node:
            return (started.node,)
        others = {s.node for s in self.started.values() if s is not started and s.node}
        mine = rospy.get_name()
        return tuple(sorted(r.node for r in new_registrations(started.before)
                            if r.node not in others and r.node != mine))

    def who(self, nodes: Optional[Sequence[str]]) -> str:
        """The node(s) in words, for a failure message."""
        if nodes is None:
            return "no node"
        return "node %s" % ", ".join(nodes) if nodes else "no node of it"

    def registered(self, nodes: Optional[Sequence[str]]):
        """The current registrations of `nodes` (every node but ours when None)."""
        state = system_state()
        mine = rospy.get_name()
        if nodes is None:
            return [r for n, r in state.items() if n != mine]
        return [state[n] for n in nodes if n in state]

    # -- the last action ----------------------------------------------------------------------------

    def action(self, words: str = "") -> None:
        """An action step begins (`words`: what it does, as a failure after it names it): what the
        processes printed so far and the turtles' poses are 'before'."""
        self.last_action = words
        for hook in self.on_action:
            hook(self)
        self.action_time = time.monotonic()
        self.output_marks = {name: len(s.output()) for name, s in self.started.items()}
        self.pose_marks = {name: r.count for name, r in self.pose_recorders.items()}

    def after_action(self) -> str:
        """'after <the last action>', for a check's failure."""
        return "after %s" % (self.last_action or "the last action")

    def output_since_action(self, started: Started) -> str:
        return started.output()[self.output_marks.get(started.name, 0):]

    # -- the end --------------------------------------------------------------------------------------

    def close(self) -> None:
        """Every started process ended, every subscription and publisher of the steps gone."""
        for started in self.started.values():
            started.process.end()
        for recorder in self.pose_recorders.values():
            recorder.unregister()
        for close in self.closers:
            close()
