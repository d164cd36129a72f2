"""The class's files under the output folder, written from every student's verdicts: gradebook.csv,
milestones.csv and failure_groups.csv (class_view), similarity.csv (similarity) and report.html.
A regrade (grade --regrade STUDENT) writes them again from the regraded student's new verdicts and
everyone else's as their results.json holds them, so nobody else's verdict changes."""
from __future__ import annotations

import csv
import os
from typing import Callable, Dict, List, Sequence

from course_format.milestone import Milestone

from course_grader import class_view, gradebook, gradescope, report, similarity
from course_grader.verdict import Verdict

GRADEBOOK = "gradebook.csv"
REPORT = "report.html"
RESULTS = "results.json"
# Under the output folder, beside the students' folders: each student's unpacked files, workspace and
# runs; no student name starts with "_" (submissions.student_name).
WORK_DIR = "_work"


def unpacked(out: str, student: str) -> str:
    """Where the grader unpacked a student's submission (their files as handed in)."""
    return os.path.join(out, WORK_DIR, student, "files")


def write(out: str, verdicts: Sequence[Verdict], order: Sequence[Milestone], isolation: str,
          boilerplate: Sequence[str] = (), say: Callable[[str], None] = print) -> List[similarity.Pair]:
    """Every class file under `out`; returns the similar pairs (none for fewer than two students)."""
    gradebook.write(os.path.join(out, GRADEBOOK), verdicts, order)
    class_view.write_csvs(out, verdicts, order)
    students = list(dict.fromkeys(v.student for v in verdicts))
    pairs: List[similarity.Pair] = []
    if len(students) > 1:
        try:
            pairs = similarity.find({s: unpacked(out, s) for s in students}, boilerplate)
        except ImportError as err:  # the venv without copydetect (setup/install.sh installs it)
            say("similarity: not computed (%s)" % err)
    similarity.write_csv(os.path.join(out, similarity.CSV_NAME), pairs)
    report.write(os.path.join(out, REPORT), verdicts, order, isolation, pairs)
    return pairs


def earlier_students(out: str) -> List[str]:
    """The students of an earlier grading in `out`: the gradebook's order, then any other folder
    holding a results.json."""
    names: List[str] = []
    try:
        with open(os.path.join(out, GRADEBOOK), newline="") as f:
            names = [row[0] for row in list(csv.reader(f))[1:] if row]
    except OSError:
        pass
    others = sorted(e for e in os.listdir(out) if not e.startswith("_") and e not in names
                    and os.path.isfile(os.path.join(out, e, RESULTS)))
    return [n for n in names + others if os.path.isfile(os.path.join(out, n, RESULTS))]


def merged(out: str, student: str, regraded: Sequence[Verdict], order: Sequence[Milestone]) -> List[Verdict]:
    """The class's verdicts after regrading `student`: theirs from `regraded`, everyone else's from
    their results.json, in the earlier gradebook's order (a new student last)."""
    milestones: Dict[str, Milestone] = {m.name: m for m in order}
    found: List[Verdict] = []
    students = earlier_students(out)
    for name in students + ([] if student in students else [student]):
        if name == student:
            found += regraded
        else:
            found += gradescope.load(os.path.join(out, name, RESULTS), name, milestones, os.path.join(out, name))
    return found
