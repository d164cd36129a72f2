"""A milestone run's gate: its rostest may start before the student's overlay is built, and its
check waits here before it does anything with the student's packages.

The grader starts a submission's first runs while CMake configures the overlay on one core (the
other is idle then): rostest's master, the world's simulators and the check's own start-up need
nothing of the student. Each such check then waits in `wait()` until the grader decides, once,
through a file named by $COURSE_RUN_GATE:
- `go`: the overlay is built and the run's sandbox policy is written; the check goes on as if it
  had just started;
- `stop`: the run is void (the build failed, or took too long and the run starts again from
  scratch); the check ends without testing anything, and the grader discards what it reports.

Without the variable (a plain `rostest`, `make test`, a run started after the build) there is no
gate and `wait()` returns at once.
"""
from __future__ import annotations

import os
import time
from typing import Dict, Optional

ENV_VAR = "COURSE_RUN_GATE"
GO = "go"
STOP = "stop"
POLL_S = 0.05
# A check never waits longer: the grader decides within its build's time (course_grader.runner
# gives up on a run started early well before this) and a gate nobody opens is a grader's bug.
WAIT_LIMIT_S = 120.0


class GateError(RuntimeError):
    """The gate was never decided, or says something else than go or stop."""


def decide(path: str, go: bool) -> None:
    """Write the decision atomically: a check never reads half a word."""
    part = path + ".part"
    with open(part, "w") as f:
        f.write(GO if go else STOP)
    os.replace(part, path)


def read(path: str) -> Optional[str]:
    """The decision written at `path`, or None while there is none."""
    try:
        with open(path) as f:
            word = f.read().strip()
    except FileNotFoundError:
        return None
    if word not in (GO, STOP):
        raise GateError("the run's gate %s says %r, not %s or %s" % (path, word, GO, STOP))
    return word


def wait(environ: Optional[Dict[str, str]] = None, limit: float = WAIT_LIMIT_S) -> bool:
    """Block until this run's gate is decided: True to go on (or no gate), False to stop."""
    path = (os.environ if environ is None else environ).get(ENV_VAR)
    if not path:
        return True
    deadline = time.monotonic() + limit
    word = read(path)
    while word is None:
        if time.monotonic() > deadline:
            raise GateError("the grader did not open this run's gate within %.0f s" % limit)
        time.sleep(POLL_S)
        word = read(path)
    return word == GO
