"""What the ROS master said last, kept so that many questions cost one round of XML-RPC calls.

`CachedMaster` is a course_web.introspect Master itself: introspect's graph, topics, plot and
health answer from it as from the real one. It asks the real master only when told to
(`refresh`), and then as little as it can: getSystemState each time (the one call that tells
whether anything changed, and whether the master answers at all), getTopicTypes only when the
system state changed or its last answer is older than `types_period_s` (a type changes only when
a node registers, which shows in the state), and a node's liveness (its getPid) at most once per
`liveness_period_s`, or again after the state changed. `version` goes up whenever what it knows
changes, so whoever turns its answers into words can skip the work when it has not.

Not thread-safe: its owner (course_web.lab_status) holds a lock around every use. Time is passed
in (a clock), so tests step it.
"""
from __future__ import annotations

import math
from typing import Callable, Dict, Iterable, Mapping, Optional, Sequence, Tuple

from course_web.introspect import ApiError, Master

TYPES_PERIOD_S = 30.0
LIVENESS_PERIOD_S = 3.0

Rows = Tuple[Tuple[str, Tuple[str, ...]], ...]
State = Tuple[Rows, Rows, Rows]


def normalised(state: Sequence[Sequence]) -> State:
    """getSystemState's answer with its rows and node lists sorted, so two answers compare equal
    exactly when the registrations are the same."""
    def rows(table: Iterable[Sequence]) -> Rows:
        return tuple(sorted((str(name), tuple(sorted(str(n) for n in nodes))) for name, nodes in table))
    if len(state) != 3:
        raise ValueError("getSystemState answered %d lists, not 3" % len(state))
    return rows(state[0]), rows(state[1]), rows(state[2])


class CachedMaster:
    """See the module docstring."""

    def __init__(self, master: Master, clock: Callable[[], float],
                 types_period_s: float = TYPES_PERIOD_S, liveness_period_s: float = LIVENESS_PERIOD_S) -> None:
        self.master = master
        self.clock = clock
        self.types_period_s = types_period_s
        self.liveness_period_s = liveness_period_s
        self.version = 0
        self.taken = -math.inf        # when getSystemState was last asked (answered or not)
        self._state: Optional[State] = None
        self._down: Optional[ApiError] = None   # why the master did not answer, the last time
        self._types: Dict[str, str] = {}
        self._types_taken = -math.inf
        self._alive: Dict[str, Tuple[bool, float]] = {}  # node -> (answers, when asked)

    def age(self) -> float:
        """Seconds since the state was last asked (infinite before the first time)."""
        return self.clock() - self.taken

    def refresh(self) -> None:
        """Ask the master its system state (and the topic types when due)."""
        now = self.taken = self.clock()
        try:
            state = normalised(self.master.system_state())
            changed = state != self._state or self._down is not None
            if changed or now - self._types_taken >= self.types_period_s:
                types = dict(self.master.topic_types())
                self._types_taken = now
                changed = changed or types != self._types
                self._types = types
        except ApiError as err:
            if self._down is None or str(self._down) != str(err) or self._state is not None:
                self._bump()
            self._state, self._down = None, err
            self._types, self._types_taken = {}, -math.inf
            return
        if changed:
            self._state, self._down = state, None
            self._alive.clear()  # who publishes what changed: ask the nodes again
            self._bump()

    def refresh_if_older(self, seconds: float) -> None:
        if self.age() >= seconds:
            self.refresh()

    def check_nodes(self, names: Iterable[str]) -> None:
        """Ask each node whether it answers, unless it was asked within the liveness period."""
        for name in names:
            self.node_answers(name)

    def _bump(self) -> None:
        self.version += 1

    # -- course_web.introspect.Master, from what was asked last -----------------------------
    def system_state(self) -> Sequence[Sequence]:
        if self._state is None:
            if self._down is not None:
                raise ApiError(str(self._down), self._down.status)
            self.refresh()
            return self.system_state()
        return self._state

    def topic_types(self) -> Mapping[str, str]:
        self.system_state()  # raises when the master did not answer
        return dict(self._types)

    def node_answers(self, name: str) -> bool:
        now = self.clock()
        known = self._alive.get(name)
        if known is not None and now - known[1] < self.liveness_period_s:
            return known[0]
        answers = bool(self.master.node_answers(name))
        self._alive[name] = (answers, now)
        if known is not None and known[0] != answers:
            self._bump()
        return answers
