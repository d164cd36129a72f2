"""Which keys a student's keyboard controller uses, found by pressing keys and watching its commands.

The texts fix what the keys must do (001 #2.1.10: the arrow keys move the turtle; 002 section 4:
forward, backward, turn left, turn right, with single keys or `raw_input()` lines), not which keys.
Public solutions use the arrows, w/a/s/d (s or x backwards), z/q/s/d on AZERTY keyboards, i/j/k/l,
or the keypad digits, each read one key at a time or as a line ended by Enter.

This module is the pure part of the search: which key to press next, what a velocity command
means, and the sentence a student reads when a direction is missing. The ROS side
(course_milestones.keyboard_probe) types the keys and records the commands.
"""
from __future__ import annotations

import math
from typing import Dict, List, NamedTuple, Optional, Sequence, Tuple

from course_milestones import causes

FORWARD, BACKWARD, LEFT, RIGHT = "forward", "backward", "left", "right"
DIRECTIONS = (FORWARD, BACKWARD, LEFT, RIGHT)  # also the search order: each differs from the one before
EXPECTED = {FORWARD: "linear.x > 0", BACKWARD: "linear.x < 0", LEFT: "angular.z > 0", RIGHT: "angular.z < 0"}
WORDS = {FORWARD: "go forward", BACKWARD: "go backward", LEFT: "turn left", RIGHT: "turn right"}


class Layout(NamedTuple):
    """A family of key maps: the candidate keys for each direction, the usual one first.
    Key names 'up', 'down', 'left', 'right' are the arrow keys; anything else is typed as is."""

    name: str
    keys: Dict[str, Tuple[str, ...]]


ARROW_KEYS = ("up", "down", "left", "right")
LAYOUTS: Tuple[Layout, ...] = (
    Layout("arrows", {FORWARD: ("up",), BACKWARD: ("down",), LEFT: ("left",), RIGHT: ("right",)}),
    Layout("w/a/s/d", {FORWARD: ("w",), BACKWARD: ("s", "x"), LEFT: ("a",), RIGHT: ("d",)}),
    Layout("z/q/s/d", {FORWARD: ("z",), BACKWARD: ("s",), LEFT: ("q",), RIGHT: ("d",)}),
    Layout("i/j/k/l", {FORWARD: ("i",), BACKWARD: ("k", ","), LEFT: ("j",), RIGHT: ("l",)}),
    Layout("keypad 8/4/2/6", {FORWARD: ("8",), BACKWARD: ("2", "5"), LEFT: ("4",), RIGHT: ("6",)}),
)


def answers(direction: str, linear_x: float, angular_z: float, eps: float = 1e-6) -> bool:
    """Whether a command (linear.x, angular.z) does what `direction` asks."""
    if not (math.isfinite(linear_x) and math.isfinite(angular_z)):
        return False
    return {FORWARD: linear_x > eps, BACKWARD: linear_x < -eps,
            LEFT: angular_z > eps, RIGHT: angular_z < -eps}[direction]


def key_label(key: str, enter: bool = False) -> str:
    """How a key is named to the student: 'up', 'w', 'w + Enter'."""
    name = key if key in ARROW_KEYS else repr(key)
    return name + (" + Enter" if enter else "")


def wrap_angle(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))


def moved(direction: str, before: Tuple[float, float, float], after: Tuple[float, float, float],
          min_distance: float, min_angle: float) -> bool:
    """Whether a robot at pose (x, y, theta) `before` is now at `after` having gone `direction`:
    along its heading for forward/backward, counter-clockwise for left, clockwise for right."""
    (x0, y0, th0), (x1, y1, th1) = before, after
    along = (x1 - x0) * math.cos(th0) + (y1 - y0) * math.sin(th0)
    turned = wrap_angle(th1 - th0)
    return {FORWARD: along > min_distance, BACKWARD: along < -min_distance,
            LEFT: turned > min_angle, RIGHT: turned < -min_angle}[direction]


class Probe(NamedTuple):
    """One key press to try: which direction it should give, the key, and whether Enter follows."""

    direction: str
    key: str
    enter: bool


def stale_bytes_risk(pressed: Sequence[Probe], probe: Probe) -> bool:
    """Whether `probe` (a single key) may be read wrong because an arrow key pressed before went
    unanswered. A node reading keys with select() and sys.stdin.read(1) takes the arrow's three
    bytes into Python's buffer, uses one and leaves two, which it reads on the next key presses
    instead of those keys: a node that does not use arrows must be started afresh before other
    keys are tried."""
    return len(probe.key) == 1 and any(p.key in ARROW_KEYS and not p.enter for p in pressed)


class Outcome(NamedTuple):
    """What came back after a press: the commands (linear.x, angular.z) seen after it, and whether
    the node was still running."""

    commands: Tuple[Tuple[float, float], ...] = ()
    exited: bool = False

    def answered(self, direction: str) -> bool:
        return any(answers(direction, lin, ang) for lin, ang in self.commands)


class KeyMap(NamedTuple):
    """The keys found: direction -> key, and whether each key is followed by Enter."""

    layout: str
    keys: Dict[str, str]
    enter: bool

    def describe(self) -> str:
        keys = ", ".join("%s=%s" % (d, key_label(self.keys[d])) for d in DIRECTIONS if d in self.keys)
        return "%s%s (%s)" % (self.layout, " + Enter" if self.enter else "", keys)


class SearchResult(NamedTuple):
    """The key map found (None if no key made the robot go forward), the directions no key gave,
    with what was pressed and seen for each, whether the node exited during the search, and the
    command (linear.x, angular.z) each key found gave."""

    keymap: Optional[KeyMap]
    missing: Dict[str, List[Tuple[Probe, Outcome]]]
    exited_after: Optional[Probe]
    commands: Dict[str, Tuple[float, float]]
    presses: int = 0

    @property
    def complete(self) -> bool:
        return self.keymap is not None and not self.missing and self.exited_after is None


class KeyMapSearch:
    """Decides which key to press next until every direction has a key or the candidates run out.

    First the forward key: every layout's forward keys, each alone and then followed by Enter,
    `rounds` times over (a press typed while a node is still setting up its terminal can be lost).
    The first that answers, and answers again when pressed once more (a slow answer to the
    previous key must not pass for this one's; the very first press needs no second), fixes the
    layout and whether Enter is needed; then the backward, left and right keys of that layout are
    tried, each up to `tries` times while it does not answer (a press can be lost). `first`, a key
    map found before (e.g. on the same node under another launch file), is tried first.
    """

    def __init__(self, layouts: Sequence[Layout] = LAYOUTS, first: Optional[KeyMap] = None,
                 rounds: int = 2, tries: int = 2) -> None:
        self.layouts = {layout.name: layout for layout in layouts}
        self.tries = tries
        self._queue: List[Probe] = []
        if first is not None:
            self._queue.append(Probe(FORWARD, first.keys[FORWARD], first.enter))
        for _ in range(rounds):
            for layout in layouts:
                for key in layout.keys[FORWARD]:
                    self._queue += [Probe(FORWARD, key, False), Probe(FORWARD, key, True)]
        self._first = first
        self._layout_of_forward = {key: layout.name for layout in reversed(layouts) for key in layout.keys[FORWARD]}
        self.keymap: Optional[KeyMap] = None
        self.missing: Dict[str, List[Tuple[Probe, Outcome]]] = {}
        self.exited_after: Optional[Probe] = None
        self.commands: Dict[str, Tuple[float, float]] = {}
        self._silent: Dict[Probe, int] = {}
        self._candidate: Optional[Probe] = None
        self.presses = 0

    def next_probe(self) -> Optional[Probe]:
        if self.exited_after is not None or not self._queue:
            return None
        return self._queue[0]

    def record(self, probe: Probe, outcome: Outcome) -> None:
        """Take in what a press of `probe` (the one next_probe() gave) produced."""
        self._queue.pop(0)
        self.presses += 1
        if outcome.answered(probe.direction):
            self.commands[probe.direction] = [c for c in outcome.commands if answers(probe.direction, *c)][-1]
        if probe.direction == FORWARD and self.keymap is None:
            candidate, self._candidate = self._candidate, None
            if outcome.answered(FORWARD) and (candidate == probe or self.presses == 1):
                self._found_forward(probe)
            elif outcome.answered(FORWARD):
                self._candidate = probe
                self._queue.insert(0, probe)  # press it once more to be sure it is this key's answer
            elif outcome.exited:
                self.exited_after = probe
            else:
                self.missing.setdefault(FORWARD, []).append((probe, outcome))
            return
        if outcome.answered(probe.direction):
            self.keymap.keys[probe.direction] = probe.key
            self._queue = [p for p in self._queue if p.direction != probe.direction]
            self.missing.pop(probe.direction, None)
            return
        self.missing.setdefault(probe.direction, []).append((probe, outcome))
        if outcome.exited:
            self.exited_after = probe
            return
        self._silent[probe] = self._silent.get(probe, 0) + 1
        if self._silent[probe] < self.tries:
            self._queue.insert(0, probe)  # the press may have been lost: press the same key again

    def skip(self) -> None:
        """Drop the next probe unpressed (e.g. a key + Enter for a node seen reading single keys)."""
        self._queue.pop(0)

    def _found_forward(self, probe: Probe) -> None:
        if self._first is not None and probe.key == self._first.keys[FORWARD] and probe.enter == self._first.enter:
            layout = self.layouts.get(self._first.layout) or Layout(self._first.layout, {})
            keys = {d: (self._first.keys[d],) + tuple(k for k in layout.keys.get(d, ()) if k != self._first.keys[d])
                    for d in DIRECTIONS if d in self._first.keys}
            layout = Layout(self._first.layout, keys)
        else:
            layout = self.layouts[self._layout_of_forward[probe.key]]
        self.keymap = KeyMap(layout.name, {FORWARD: probe.key}, probe.enter)
        self.missing.pop(FORWARD, None)
        self._queue = [Probe(d, key, probe.enter) for d in DIRECTIONS[1:] for key in layout.keys.get(d, ())]

    def result(self) -> SearchResult:
        return SearchResult(self.keymap, dict(self.missing), self.exited_after, dict(self.commands), self.presses)


def _seen(outcome_list: Sequence[Tuple[Probe, Outcome]]) -> str:
    commands = [c for _, o in outcome_list for c in o.commands]
    if not commands:
        return "none"
    shown = sorted(set((round(lin, 3), round(ang, 3)) for lin, ang in commands))[:3]
    return ", ".join("linear.x=%g angular.z=%g" % c for c in shown)


def _keys_tried(outcome_list: Sequence[Tuple[Probe, Outcome]]) -> str:
    labels: List[str] = []
    for probe, _ in outcome_list:
        label = key_label(probe.key, probe.enter)
        if label not in labels:
            labels.append(label)
    return ", ".join(labels)


def failure_message(result: SearchResult, topic: str, subject: str) -> Optional[causes.Finding]:
    """The sentence telling the student which direction no key gave, naming the keys pressed and
    the commands seen on `topic` (cause not_moving; node_exited when the controller exited); None
    when all four directions were found. `subject` names what is driven ('turtle1', 'the Burger')."""
    if result.exited_after is not None and (result.keymap is None or result.missing):
        return causes.finding("node_exited", "the controller exited after the key %s was pressed (keys found so far: "
                              "%s)" % (key_label(result.exited_after.key, result.exited_after.enter),
                                       result.keymap.describe() if result.keymap else "none"))
    if result.keymap is None:
        tried = result.missing.get(FORWARD, [])
        return causes.finding("not_moving", "no key made %s go forward: after each of %s, %s got no command with %s "
                              "(commands seen: %s)" % (subject, _keys_tried(tried), topic, EXPECTED[FORWARD],
                                                       _seen(tried)))
    missing = ["no key made %s %s: after pressing %s, %s got no command with %s (commands seen: %s)"
               % (subject, WORDS[d], _keys_tried(result.missing[d]), topic, EXPECTED[d], _seen(result.missing[d]))
               for d in DIRECTIONS if d in result.missing]
    if missing:
        return causes.finding("not_moving", "with the %s key map (%s), %s" % (result.keymap.layout,
                                                                              result.keymap.describe(),
                                                                              "; ".join(missing)))
    return None


def scaled(before: float, after: float, factor: float, rel: float = 1e-3) -> bool:
    """Whether a command `after` is `factor` times `before` (001 #2.3.7: the command is the scale
    parameter times the node's own speed, so it follows the parameter)."""
    return math.isclose(after, before * factor, rel_tol=rel, abs_tol=1e-6)
