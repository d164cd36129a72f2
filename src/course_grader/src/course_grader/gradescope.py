"""Gradescope's results.json for one submission (gradescope-autograders.readthedocs.io, specs):
top-level score, execution_time, output, visibility, stdout_visibility, tests[] with name,
number, score, max_score, status ("passed"/"failed"), output and visibility; each test's
extra_data (a field of the spec Gradescope stores and does not show) holds what the class view
needs: the milestone's name, the run's seconds and the failure's cause key. `load` reads the
verdicts back, so a class's outputs can be written again from its students' results.json
(grade --regrade)."""
from __future__ import annotations

import json
from typing import Dict, List, Mapping, Sequence

from course_format.milestone import Milestone

from course_grader.verdict import FAILED, Verdict


def results(verdicts: Sequence[Verdict], execution_time: float, note: str = "") -> Dict:
    tests = []
    for number, v in enumerate(verdicts, 1):
        tests.append({
            "name": "%s: %s (%s)" % (v.milestone.name, v.milestone.title, v.milestone.text),
            "number": str(number),
            "score": float(v.points),
            "max_score": float(v.milestone.points),
            "status": "passed" if v.passed else "failed",
            "output": v.output(),
            "visibility": "visible",
            "extra_data": {"milestone": v.milestone.name, "seconds": round(v.elapsed, 1), "cause": v.cause_key},
        })
    passed = sum(v.passed for v in verdicts)
    summary = "%d of %d milestones passed." % (passed, len(verdicts))
    return {
        "score": float(sum(v.points for v in verdicts)),
        "execution_time": int(round(execution_time)),
        "output": summary + ("\n" + note if note else ""),
        "visibility": "visible",
        "stdout_visibility": "hidden",
        "tests": tests,
    }


def write(path: str, verdicts: Sequence[Verdict], execution_time: float, note: str = "") -> None:
    with open(path, "w") as f:
        json.dump(results(verdicts, execution_time, note), f, indent=2)


def load(path: str, student: str, milestones: Mapping[str, Milestone], artifacts_root: str = "") -> List[Verdict]:
    """The verdicts a results.json written by `write` holds, for milestones still in `milestones`
    (by name). What the student read (output) comes back as the reason of a failure, the logs of
    a pass; `artifacts_root`/<milestone> is where the run's pictures are. Raises OSError or
    ValueError for a file that is missing or not such a results.json."""
    with open(path) as f:
        data = json.load(f)
    found = []
    for test in data.get("tests", []):
        extra = test.get("extra_data") or {}
        name = extra.get("milestone") or str(test.get("name", "")).split(":", 1)[0]
        if name not in milestones:
            continue
        passed = test.get("status") == "passed"
        output = str(test.get("output", ""))
        reason, logs = ("", output[len("passed"):].strip()) if passed else (output[len(FAILED):]
                                                                          if output.startswith(FAILED) else output, "")
        found.append(Verdict(student, milestones[name], passed, reason, logs, float(extra.get("seconds", 0.0)),
                             "%s/%s" % (artifacts_root, name) if artifacts_root else "", "",
                             str(extra.get("cause", ""))))
    return found
