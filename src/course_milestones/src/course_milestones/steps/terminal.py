"""The terminal steps: `prints` (the student's node printed a line matching a pattern since the
last action) and `type` (keys typed on its terminal, as a student types them)."""
from __future__ import annotations

import re
import time
from typing import Dict, List

from course_milestones import students
from course_milestones.students import RAW_WAIT
from course_milestones.steps.state import StepState, course_error, failed
from course_checks.waiting import wait_for

TAIL_CHARS = 300
# Keys a `type` step names in angle brackets; anything else is typed as it is.
NAMED_KEYS = {"<up>": "up", "<down>": "down", "<left>": "left", "<right>": "right", "<enter>": "\n",
              "<space>": " ", "<esc>": "\x1b"}
_KEY = re.compile("|".join(re.escape(k) for k in NAMED_KEYS) + "|.", re.DOTALL)


def keys_of(text: str) -> List[str]:
    """The keys a `type` step's text stands for: each character, or a named key such as <up>."""
    return [NAMED_KEYS.get(k, k) for k in _KEY.findall(text)]


def prints(state: StepState, p: Dict, where: str) -> None:
    try:
        pattern = re.compile(p["pattern"], re.MULTILINE)
    except re.error as err:
        raise course_error(where, "pattern %r is not a regular expression (%s)" % (p["pattern"], err)) from None
    started = state.process(p.get("node"), where)
    within = float(p.get("within") or 0)
    if wait_for(lambda: pattern.search(state.output_since_action(started)), within, 0.05):
        return
    output = started.output()
    ended = "" if started.process.node.running() else " (it exited with status %s)" % (
        started.process.node.proc.returncode)
    since = state.after_action() if started.name in state.output_marks else "since it started"
    said = "its output ends with: %r" % output[-TAIL_CHARS:] if output.strip() else "it printed nothing at all"
    # a node that ended before it printed the line (a client that printed another line is not_printed)
    gone = ended and (started.node is not None or not output.strip())
    raise failed(state.exit_cause(started) if gone else "not_printed",
                 "`%s` printed no line matching %r %s (waited %g s)%s; %s"
                 % (started.command, p["pattern"], since, within, ended, said))


def type_keys(state: StepState, p: Dict, where: str) -> None:
    started = state.process(p.get("node"), where)
    keys = keys_of(str(p["keys"]))
    if not keys:
        raise course_error(where, "keys is empty")
    state.action("typing %r on `%s`" % (str(p["keys"]), started.command))
    keyboard = started.process
    keyboard.raw_wait = RAW_WAIT  # a node that reads single keys flushes what came before its raw mode
    pause = float(p.get("pause") or 0.0)
    for key in keys:
        if not keyboard.node.running():
            raise failed(state.exit_cause(started), "`%s` exited (status %s) while keys were typed on its terminal%s"
                         % (started.command, keyboard.node.proc.returncode, students.last_words(keyboard)))
        keyboard.press(key)
        time.sleep(pause)  # the text's pace of typing, not a wait for anything
