"""Gradescope's results.json for one submission (gradescope-autograders.readthedocs.io, specs):
top-level score, execution_time, output, visibility, stdout_visibility, tests[] with name,
number, score, max_score, status ("passed"/"failed"), output and visibility."""
from __future__ import annotations

import json
from typing import Dict, Sequence

from course_grader.verdict import Verdict


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
