"""Runs started before their submission's build ends, and who decides what becomes of each.

CMake configures a student's overlay on one core for 5-6 s while the other waits. A milestone
run's first seconds need nothing of the student: rostest, its master, the world's simulators and
the check's own start-up. So the grader starts a submission's first runs (the longest, which end
last) beside the build; each check waits at its gate (course_checks.run_gate) until the build
thread decides, once:
- go: the overlay built, the run's sandbox policy is written, the gate opens, the run is judged
  as any other;
- void: the build failed (or the grading stops): the gate says stop, the run's report is
  discarded, the build's own verdicts stand;
- restart: the build took so long that the waiting run's time limit would suffer: the run is
  voided and, once it has ended, started again from scratch with what the build produced.
A run that ends before anyone decided (its world failed to start, say) is abandoned: nothing of
it counts and the build thread starts that milestone as it would have without an early start.
Exactly one of the two threads ends up owning each milestone's verdict; this class is that
hand-over, without ROS or processes, so its races can be tested alone.
"""
from __future__ import annotations

import threading
import time
from typing import Callable, Optional, Tuple

from course_checks import run_gate

GO = "go"
VOID = "void"
RESTART = "restart"
ABANDONED = "abandoned"
# How long an early run may wait at its gate and still be the run that counts: a Python
# submission builds in about 10 s here; a longer (C++) build restarts the run instead, so no check
# spends much of its time limit (60 s at the least, course_milestones/test/*.test) waiting.
WAIT_LIMIT_S = 30.0


class EarlyRun:
    """One milestone run started early; `gate` is its gate file's path."""

    def __init__(self, gate: str, clock: Callable[[], float] = time.monotonic) -> None:
        self.gate = gate
        self._clock = clock
        self.started = clock()
        self.opened: Optional[float] = None
        self.outcome: Optional[str] = None
        self.hints: list = []
        self.first: list = []
        self.restart_args: Tuple = ()
        self._lock = threading.Lock()

    def stale(self, limit: Optional[float] = None) -> bool:
        """Whether it has waited too long (WAIT_LIMIT_S) to be the run that counts."""
        return self._clock() - self.started > (WAIT_LIMIT_S if limit is None else limit)

    def open(self, hints: list, first: list, write_policy: Callable[[], object]) -> bool:
        """The build is done: write the run's policy and let its check go on. False when the run
        was abandoned already (the caller starts the milestone itself)."""
        with self._lock:
            if self.outcome is not None:
                return False
            self.hints, self.first = list(hints), list(first)
            try:
                write_policy()
            except BaseException:
                run_gate.decide(self.gate, False)  # its check must not wait for a gate never opened
                self.outcome = VOID
                raise
            run_gate.decide(self.gate, True)
            self.opened = self._clock()
            self.outcome = GO
            return True

    def void(self) -> None:
        """The run must not count (build failed, grading stopped): its check ends at the gate."""
        with self._lock:
            if self.outcome is None:
                run_gate.decide(self.gate, False)
                self.outcome = VOID

    def restart(self, args: Tuple) -> bool:
        """Void the run and have its own thread run the milestone again with `args` once it has
        ended. False when the run was abandoned already (the caller starts the milestone itself)."""
        with self._lock:
            if self.outcome is not None:
                return False
            run_gate.decide(self.gate, False)
            self.restart_args = tuple(args)
            self.outcome = RESTART
            return True

    def ended(self) -> str:
        """Called by the run's thread once rostest returned: the outcome it must act on. A run
        nobody decided on yet is abandoned from now on."""
        with self._lock:
            if self.outcome is None:
                self.outcome = ABANDONED
            return self.outcome

    def waited(self) -> float:
        """Seconds the check spent at its gate (0 if it never opened)."""
        return (self.opened - self.started) if self.opened is not None else 0.0
