"""Which keys a student's keyboard controller uses, found by pressing keys and watching its commands.

The texts fix what the keys must do (001 #2.1.10: the arrow keys move the turtle; 002 section 4:
forward, backward, turn left, turn right, with single keys or `raw_input()` lines), not which keys.
Public solutions use the arrows, w/a/s/d (s or x backwards), z/q/s/d on AZERTY keyboards, i/j/k/l,
or the keypad digits, each read one key at a time or as a line ended by Enter; some swap a pair
(`d` turning left). So every key the search presses counts for whichever motion it makes: a layout
only decides which keys are tried first. After the layouts' keys come every letter, digit and
arrow (KEY_SETS), so any four distinct keys of those sets are found.

This module is the pure part of the search: which key to press next, what a velocity command
means, and the sentence a student reads when a motion is missing. The ROS side
(keyboard_probe, beside it in the course's checks/) types the keys and records the commands.
"""
from __future__ import annotations

import math
import string
from typing import Dict, List, NamedTuple, Optional, Sequence, Set, Tuple

from course_format import causes

FORWARD, BACKWARD, LEFT, RIGHT = "forward", "backward", "left", "right"
DIRECTIONS = (FORWARD, BACKWARD, LEFT, RIGHT)  # also the search order: each differs from the one before
EXPECTED = {FORWARD: "linear.x > 0", BACKWARD: "linear.x < 0", LEFT: "angular.z > 0", RIGHT: "angular.z < 0"}
WORDS = {FORWARD: "go forward", BACKWARD: "go backward", LEFT: "turn left", RIGHT: "turn right"}
MAX_RESTARTS = 3  # a node that exits on a key (q to quit, or a crash on an unknown key) is started again


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
# Letters that often do something else (quit, reset the simulator, clear the canvas): pressed last.
ACTION_LETTERS = ("c", "r", "q")
KEY_SETS: Tuple[Tuple[str, ...], ...] = (
    tuple(k for k in string.ascii_lowercase if k not in ACTION_LETTERS),
    tuple(string.digits),
    ACTION_LETTERS,
    ARROW_KEYS,  # last: a node reading single bytes leaves two of an arrow's three for the keys after it
)


def _unique(keys) -> Tuple[str, ...]:
    return tuple(dict.fromkeys(keys))


# Every key the search may press, in the order it tries them after the layout it prefers.
ALL_KEYS = _unique([k for layout in LAYOUTS for d in DIRECTIONS for k in layout.keys[d] if k not in ARROW_KEYS]
                   + [k for keys in KEY_SETS for k in keys])


def answers(direction: str, linear_x: float, angular_z: float, eps: float = 1e-6) -> bool:
    """Whether a command (linear.x, angular.z) does what `direction` asks."""
    if not (math.isfinite(linear_x) and math.isfinite(angular_z)):
        return False
    return {FORWARD: linear_x > eps, BACKWARD: linear_x < -eps,
            LEFT: angular_z > eps, RIGHT: angular_z < -eps}[direction]


class Command(NamedTuple):
    """A geometry_msgs/Twist as the search sees it: linear.x and angular.z first (what moves a
    turtle forward and round; commands[direction][0] and [1]), then the other four fields."""

    linear_x: float
    angular_z: float
    linear_y: float = 0.0
    linear_z: float = 0.0
    angular_x: float = 0.0
    angular_y: float = 0.0

    @classmethod
    def of(cls, twist) -> "Command":
        return cls(twist.linear.x, twist.angular.z, twist.linear.y, twist.linear.z, twist.angular.x, twist.angular.y)

    def does(self, direction: str) -> bool:
        return answers(direction, self.linear_x, self.angular_z)

    def describe(self) -> str:
        """linear.x and angular.z, and every other field that is not zero, in the message's order:
        'linear.x=0 linear.y=1 angular.z=0'."""
        fields = (("linear.x", self.linear_x, True), ("linear.y", self.linear_y, False),
                  ("linear.z", self.linear_z, False), ("angular.x", self.angular_x, False),
                  ("angular.y", self.angular_y, False), ("angular.z", self.angular_z, True))
        return " ".join("%s=%g" % (name, value) for name, value, always in fields if always or value != 0)


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
    """One key press to try: the direction it is the usual key for (None: any), the key, and
    whether Enter follows."""

    direction: Optional[str]
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
    """What came back after a press: the Commands seen after it, and whether the node was still
    running."""

    commands: Tuple[Command, ...] = ()
    exited: bool = False

    def answered(self, direction: str) -> bool:
        return any(c.does(direction) for c in self.commands)

    def directions(self) -> Tuple[str, ...]:
        return tuple(d for d in DIRECTIONS if self.answered(d))


class KeyMap(NamedTuple):
    """The keys found: direction -> key, whether each key is followed by Enter, and the layout
    they belong to ('custom' if none holds them all)."""

    layout: str
    keys: Dict[str, str]
    enter: bool

    def describe(self) -> str:
        keys = ", ".join("%s=%s" % (d, key_label(self.keys[d])) for d in DIRECTIONS if d in self.keys)
        return "%s%s (%s)" % (self.layout, " + Enter" if self.enter else "", keys)


class SearchResult(NamedTuple):
    """The key map found (None if no key made any of the four motions), the directions no key
    gave, with what was pressed and seen while each was looked for, whether the node exited more
    often than it is started again (the press after which it last did), the Command each key
    found gave, and the keys after which the node exited."""

    keymap: Optional[KeyMap]
    missing: Dict[str, List[Tuple[Probe, Outcome]]]
    exited_after: Optional[Probe]
    commands: Dict[str, Command]
    presses: int = 0
    exited_on: Tuple[Probe, ...] = ()

    @property
    def complete(self) -> bool:
        return self.keymap is not None and not self.missing and self.exited_after is None


def layout_of(keys: Dict[str, str], layouts: Sequence[Layout] = LAYOUTS) -> str:
    """The name of the first layout holding every key found for its direction; 'custom' if none."""
    for layout in layouts:
        if all(key in layout.keys.get(d, ()) for d, key in keys.items()):
            return layout.name
    return "custom"


class KeyMapSearch:
    """Decides which key to press next until every direction has a key or the candidates run out.

    First, a key that makes any of the four motions: every layout's forward key, alone and then
    followed by Enter, `rounds` times over (a press typed while a node is still setting up its
    terminal can be lost), then every other key of ALL_KEYS alone and with Enter (`in_extension`).
    The first that answers, and answers again when pressed once more (a slow answer to the
    previous key must not pass for this one's; the very first press needs no second), fixes
    whether Enter is needed and the layout tried first. Then the keys of that layout for the
    motions still missing (each up to `tries` times while it gives no command at all: a press
    can be lost), then every other key once, except those the first search already pressed the
    same way and saw make none of the four motions. Any press counts for whichever motion it makes.
    `first`, a key map found before (e.g. on the same node under another launch file), is tried
    first. A node that exits after a key is started again (`restart_due`, then restarted()) up to
    `max_restarts` times, and that key is not pressed again.
    """

    def __init__(self, layouts: Sequence[Layout] = LAYOUTS, first: Optional[KeyMap] = None,
                 rounds: int = 2, tries: int = 2, max_restarts: int = MAX_RESTARTS) -> None:
        self.layouts = tuple(layouts)
        self.tries = tries
        self.max_restarts = max_restarts
        self._queue: List[Probe] = []
        if first is not None:
            self._queue.append(Probe(FORWARD, first.keys[FORWARD], first.enter))
        forward_keys = _unique(k for layout in layouts for k in layout.keys[FORWARD])
        for _ in range(rounds):
            self._queue += [Probe(FORWARD, k, enter) for k in forward_keys for enter in (False, True)]
        skipped = set(forward_keys) | ({first.keys[FORWARD]} if first is not None else set())
        self._extension = [Probe(_usual_direction(k, layouts), k, enter)
                           for k in ALL_KEYS if k not in skipped for enter in (False, True)]
        self._queue += self._extension
        self._first = first
        self.keymap: Optional[KeyMap] = None
        self.missing: Dict[str, List[Tuple[Probe, Outcome]]] = {FORWARD: []}
        self.exited_after: Optional[Probe] = None
        self.exited_on: List[Probe] = []
        self.restart_due = False
        self.commands: Dict[str, Command] = {}
        self._silent: Dict[Probe, int] = {}
        self._patient: Set[str] = set()  # keys pressed up to `tries` times while silent
        self._candidate: Optional[Tuple[Probe, Tuple[str, ...]]] = None
        self.presses = 0

    # -- what to press ---------------------------------------------------------------------
    def next_probe(self) -> Optional[Probe]:
        if self.exited_after is not None:
            return None
        quits = {p.key for p in self.exited_on}
        used = set(self.keymap.keys.values()) if self.keymap else set()
        while self._queue and (self._queue[0].key in quits or self._queue[0].key in used):
            self._queue.pop(0)
        return self._queue[0] if self._queue else None

    @property
    def in_extension(self) -> bool:
        """Whether the next press is one of the first search's keys beyond the layouts' forward keys
        (the ROS side then presses only the kind, single keys or lines, the terminal reads)."""
        return self.keymap is None and bool(self._queue) and self._queue[0] in self._extension

    @property
    def arrows_answered(self) -> bool:
        return self.keymap is not None and any(k in ARROW_KEYS for k in self.keymap.keys.values())

    def wanted(self) -> Tuple[str, ...]:
        """The directions still without a key."""
        return tuple(d for d in DIRECTIONS if self.keymap is None or d not in self.keymap.keys)

    def suits(self, probe: Probe, seen_raw: bool) -> bool:
        """Whether `probe` can reach a node whose terminal was (`seen_raw`) or was never seen in raw
        mode: a node seen reading single keys gets no lines; in the extension, a node never seen
        reading single keys (after all the first rounds) reads lines, and gets no single keys."""
        return not ((probe.enter and seen_raw) or (not probe.enter and not seen_raw and self.in_extension))

    def skip(self) -> None:
        """Drop the next probe unpressed (e.g. a key + Enter for a node seen reading single keys)."""
        self._queue.pop(0)

    def restarted(self) -> None:
        """The node was started again after it exited (restart_due)."""
        self.restart_due = False

    # -- what came back --------------------------------------------------------------------
    def record(self, probe: Probe, outcome: Outcome) -> Tuple[str, ...]:
        """Take in what a press of `probe` (the one next_probe() gave) produced; the directions
        it gave a key to."""
        self._queue.pop(0)
        self.presses += 1
        gave = tuple(d for d in outcome.directions() if d in self.wanted())
        if self.keymap is None:
            return self._record_first(probe, outcome, gave)
        for direction in self.wanted():
            if direction not in gave:
                self.missing.setdefault(direction, []).append((probe, outcome))
        for direction in gave:
            self._assign(direction, probe, outcome)
        if outcome.exited:
            self._exited(probe)
        elif not gave:
            self._silent[probe] = self._silent.get(probe, 0) + 1
            if probe.key in self._patient and self._silent[probe] < self.tries:
                self._queue.insert(0, probe)  # the press may have been lost: press the same key again
        if not self.wanted():
            self._queue = []
        return gave

    def _record_first(self, probe: Probe, outcome: Outcome, gave: Tuple[str, ...]) -> Tuple[str, ...]:
        candidate, self._candidate = self._candidate, None
        if gave and ((candidate is not None and candidate[0] == probe) or self.presses == 1):
            gave = tuple(d for d in gave if candidate is None or d in candidate[1]) or gave
            self._found(probe, outcome, gave)
            return gave
        self.missing[FORWARD].append((probe, outcome))
        if gave:
            self._candidate = (probe, gave)
            self._queue.insert(0, probe)  # press it once more to be sure it is this key's answer
        elif outcome.exited:
            self._exited(probe)
        return ()

    def _exited(self, probe: Probe) -> None:
        self.exited_on.append(probe)
        if len(self.exited_on) > self.max_restarts:
            self.exited_after = probe
        else:
            self.restart_due = True

    def _assign(self, direction: str, probe: Probe, outcome: Outcome) -> None:
        self.keymap.keys[direction] = probe.key
        self.commands[direction] = [c for c in outcome.commands if c.does(direction)][-1]
        self.missing.pop(direction, None)
        if probe.direction not in (None, direction) and probe.direction in self.wanted():
            # a swapped pair (d turning left): the usual keys of this direction may make that one
            self._queue = [p._replace(direction=probe.direction) if p.direction == direction else p
                           for p in self._queue]
            return
        # the other usual keys of a direction found are pressed last, once: they may still make another motion
        later = [p for p in self._queue if p.direction == direction]
        self._queue = [p for p in self._queue if p.direction != direction] + later
        self._patient -= {p.key for p in later}

    def _found(self, probe: Probe, outcome: Outcome, gave: Tuple[str, ...]) -> None:
        """The first key found: it fixes Enter, and the layout whose keys come next. Every press
        before it was judged for all four motions: each counts for the motions still missing, and
        a key it showed to make none of them (pressed as the key map presses, answered by no
        motion, the node still running) is not pressed again among every other key."""
        earlier = self.missing.get(FORWARD, [])
        self.keymap = KeyMap("custom", {}, probe.enter)
        self.missing = {d: list(earlier) for d in DIRECTIONS if d not in gave}
        for direction in gave:
            self._assign(direction, probe, outcome)
        settled = {p.key for p, o in earlier if p.enter == probe.enter and not o.directions() and not o.exited}
        preferred = self._preferred(probe.key, probe.enter, gave)
        self._patient = {k for keys in preferred.values() for k in keys}
        order = [(d, k) for d in DIRECTIONS if d not in gave for k in preferred.get(d, ())]
        order += [(_usual_direction(k, self.layouts), k) for k in ALL_KEYS if k not in settled]
        seen: Set[str] = set()
        self._queue = []
        for direction, key in order:
            if key not in seen and key != probe.key:
                seen.add(key)
                self._queue.append(Probe(direction, key, probe.enter))

    def _preferred(self, key: str, enter: bool, gave: Tuple[str, ...]) -> Dict[str, Tuple[str, ...]]:
        """The keys to try first for each direction: the earlier key map's if this is its key,
        else those of the first layout giving this key one of the motions it made (or holding it)."""
        first = self._first
        if first is not None and first.enter == enter and any(first.keys.get(d) == key for d in gave):
            layout = {layout.name: layout for layout in self.layouts}.get(first.layout)
            return {d: _unique(((first.keys[d],) if d in first.keys else ())
                               + (layout.keys.get(d, ()) if layout else ())) for d in DIRECTIONS}
        for layout in self.layouts:
            if any(key in layout.keys[d] for d in gave):
                return layout.keys
        for layout in self.layouts:
            if any(key in keys for keys in layout.keys.values()):
                return layout.keys
        return {}

    def result(self) -> SearchResult:
        keymap = self.keymap and self.keymap._replace(layout=layout_of(self.keymap.keys, self.layouts),
                                                      keys=dict(self.keymap.keys))
        return SearchResult(keymap, {d: list(v) for d, v in self.missing.items()}, self.exited_after,
                            dict(self.commands), self.presses, tuple(self.exited_on))


def _usual_direction(key: str, layouts: Sequence[Layout]) -> Optional[str]:
    for layout in layouts:
        for direction in DIRECTIONS:
            if key in layout.keys[direction]:
                return direction
    return None


SHOWN_KEYS = 4  # keys named in a reason; the rest are counted


def _in_order(outcome_list: Sequence[Tuple[Probe, Outcome]], direction: Optional[str]) -> List[Tuple[Probe, Outcome]]:
    """The presses, those of the usual keys for `direction` first, then in the order pressed."""
    return ([(p, o) for p, o in outcome_list if p.direction == direction]
            + [(p, o) for p, o in outcome_list if p.direction != direction])


def _seen(outcome_list: Sequence[Tuple[Probe, Outcome]], direction: Optional[str] = None) -> str:
    """The distinct commands seen, those after the usual keys for `direction` first (what the
    student meant for it), each with every field that is not zero."""
    commands = list(dict.fromkeys(c for _, o in _in_order(outcome_list, direction) for c in o.commands))
    if not commands:
        return "none"
    return ", ".join(c.describe() for c in commands[:3]) + (" and %d more" % (len(commands) - 3)
                                                           if len(commands) > 3 else "")


def _keys_tried(outcome_list: Sequence[Tuple[Probe, Outcome]], direction: Optional[str] = None) -> str:
    """The keys pressed, those usual for `direction` first, then in the order pressed; past
    SHOWN_KEYS, a count."""
    labels = list(dict.fromkeys(key_label(p.key, p.enter) for p, _ in _in_order(outcome_list, direction)))
    more = len(labels) - SHOWN_KEYS
    return ", ".join(labels[:SHOWN_KEYS]) + (" and %d more keys" % more if more > 0 else "")


def _exits(result: SearchResult) -> str:
    keys = list(dict.fromkeys(key_label(p.key, p.enter) for p in result.exited_on))
    return (" (the controller exited after %s and was started again)" % ", ".join(keys)) if keys else ""


def failure_message(result: SearchResult, topic: str, subject: str) -> Optional[causes.Finding]:
    """The sentence telling the student which motion no key gave, naming the keys pressed and
    the commands seen on `topic` (cause not_moving; when the controller kept exiting, node_exited once
    a key had moved the turtle, else exited_early);
    None when all four directions were found. `subject` names what is driven ('turtle1', 'the
    Burger')."""
    if result.exited_after is not None and (result.keymap is None or result.missing):
        return causes.finding(causes.exited(result.keymap is not None),
                              "the controller exited after the key %s was pressed, %d times in all "
                              "(keys found so far: %s)" % (key_label(result.exited_after.key, result.exited_after.enter),
                                                           len(result.exited_on),
                                                           result.keymap.describe() if result.keymap else "none"))
    if result.keymap is None:
        tried = result.missing.get(FORWARD, [])
        return causes.finding("not_moving", "no key made %s go forward, go backward, turn left or turn right: after "
                              "each of %s, %s got no command with %s (commands seen: %s)%s"
                              % (subject, _keys_tried(tried, FORWARD), topic,
                                 ", ".join(EXPECTED[d] for d in DIRECTIONS[:3]) + " or " + EXPECTED[RIGHT],
                                 _seen(tried, FORWARD), _exits(result)))
    missing = ["no key made %s %s: after pressing %s, %s got no command with %s (commands seen: %s)"
               % (subject, WORDS[d], _keys_tried(result.missing[d], d), topic, EXPECTED[d], _seen(result.missing[d], d))
               for d in DIRECTIONS if d in result.missing]
    if missing:
        return causes.finding("not_moving", "with the keys found so far, %s, %s%s" % (
            result.keymap.describe(), "; ".join(missing), _exits(result)))
    return None


def scaled(before: float, after: float, factor: float, rel: float = 1e-3) -> bool:
    """Whether a command `after` is `factor` times `before` (001 #2.3.7: the command is the scale
    parameter times the node's own speed, so it follows the parameter)."""
    return math.isclose(after, before * factor, rel_tol=rel, abs_tol=1e-6)
