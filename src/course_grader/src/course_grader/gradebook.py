"""gradebook.csv: one row per student, one column of points per milestone, and the total."""
from __future__ import annotations

import csv
from typing import Dict, List, Sequence

from course_format.milestone import Milestone

from course_grader.verdict import Verdict


def columns(verdicts: Sequence[Verdict], order: Sequence[Milestone]) -> List[Milestone]:
    """The milestones graded for anyone, in the course's order."""
    graded = {v.milestone.name for v in verdicts}
    return [m for m in order if m.name in graded]


def rows(verdicts: Sequence[Verdict], order: Sequence[Milestone]) -> List[List[str]]:
    """Header and one row per student: points per milestone ("" when not graded), total, max."""
    milestones = columns(verdicts, order)
    by_student: Dict[str, Dict[str, Verdict]] = {}
    for v in verdicts:
        by_student.setdefault(v.student, {})[v.milestone.name] = v
    table = [["student"] + [m.name for m in milestones] + ["total", "max"]]
    for student, graded in by_student.items():
        cells = ["%g" % graded[m.name].points if m.name in graded else "" for m in milestones]
        total = sum(v.points for v in graded.values())
        table.append([student] + cells + ["%g" % total, "%g" % sum(v.milestone.points for v in graded.values())])
    return table


def write(path: str, verdicts: Sequence[Verdict], order: Sequence[Milestone]) -> None:
    with open(path, "w", newline="") as f:
        csv.writer(f).writerows(rows(verdicts, order))
