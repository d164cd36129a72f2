"""The class at a glance, for a TA: per milestone how many passed and how long a run took, the
failures grouped by their cause (course_format.causes) across students, largest group first,
and the class's scores as a histogram. Written beside gradebook.csv as milestones.csv and
failure_groups.csv, shown first in report.html and, shortly, in the grader's terminal summary."""
from __future__ import annotations

import csv
import os
import statistics
import threading
from types import ModuleType
from typing import Dict, List, NamedTuple, Optional, Sequence

from course_format import causes
from course_format.milestone import Milestone

from course_grader.gradebook import columns
from course_grader.verdict import Verdict

HISTOGRAM_PNG = "scores.png"
MILESTONES_CSV = "milestones.csv"
GROUPS_CSV = "failure_groups.csv"
SUMMARY_GROUPS = 5  # the largest failure groups the terminal summary names
SUMMARY_STUDENTS = 4


class MilestoneStats(NamedTuple):
    milestone: Milestone
    graded: int
    passed: int
    median_s: float  # of the runs that ran (a build failure has no run: 0 s, left out)

    @property
    def rate(self) -> float:
        return self.passed / self.graded if self.graded else 0.0


class FailureGroup(NamedTuple):
    milestone: str
    cause: str  # a causes key
    students: List[str]

    @property
    def label(self) -> str:
        return causes.label(self.cause)


def milestone_stats(verdicts: Sequence[Verdict], order: Sequence[Milestone]) -> List[MilestoneStats]:
    found = []
    for m in columns(verdicts, order):
        graded = [v for v in verdicts if v.milestone.name == m.name]
        ran = [v.elapsed for v in graded if v.elapsed > 0]
        found.append(MilestoneStats(m, len(graded), sum(v.passed for v in graded),
                                    statistics.median(ran) if ran else 0.0))
    return found


def failure_groups(verdicts: Sequence[Verdict]) -> List[FailureGroup]:
    """Failed verdicts grouped by (milestone, cause), largest first, then by milestone and cause."""
    groups: Dict[tuple, List[str]] = {}
    for v in verdicts:
        if not v.passed:
            groups.setdefault((v.milestone.name, v.cause_key), []).append(v.student)
    made = [FailureGroup(m, c, sorted(set(s))) for (m, c), s in groups.items()]
    return sorted(made, key=lambda g: (-len(g.students), g.milestone, g.cause))


def student_totals(verdicts: Sequence[Verdict]) -> Dict[str, float]:
    """Each student's score as a percentage of the points of what they were graded on."""
    points: Dict[str, List[float]] = {}
    for v in verdicts:
        got = points.setdefault(v.student, [0.0, 0.0])
        got[0] += v.points
        got[1] += v.milestone.points
    return {s: 100.0 * p / m if m else 0.0 for s, (p, m) in points.items()}


def write_csvs(out: str, verdicts: Sequence[Verdict], order: Sequence[Milestone]) -> None:
    with open(os.path.join(out, MILESTONES_CSV), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["milestone", "graded", "passed", "median_seconds"])
        for s in milestone_stats(verdicts, order):
            w.writerow([s.milestone.name, s.graded, s.passed, "%.1f" % s.median_s])
    with open(os.path.join(out, GROUPS_CSV), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["milestone", "cause", "count", "students"])
        for g in failure_groups(verdicts):
            w.writerow([g.milestone, g.cause, len(g.students), " ".join(g.students)])


def load_plotting() -> Optional[ModuleType]:
    """pyplot on matplotlib's Agg backend (with the backend savefig() loads), or None when
    matplotlib is missing (Debian's python3-matplotlib: setup/apt-packages.txt). The first call
    imports them, 0.7 CPU s: the grader makes it on a thread of its own while the runs go on, so
    that histogram() does not spend it after the last verdict."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        from matplotlib import pyplot
        from matplotlib.backends import backend_agg  # noqa: F401 - what savefig() loads
    except ImportError:
        return None
    return pyplot


def plotting_loader() -> threading.Thread:
    """load_plotting() started on a daemon thread."""
    thread = threading.Thread(target=load_plotting, name="plotting-import", daemon=True)
    thread.start()
    return thread


def histogram(path: str, verdicts: Sequence[Verdict]) -> Optional[str]:
    """A PNG of the students' scores (percent of their points, in tenths); None when matplotlib is
    missing."""
    pyplot = load_plotting()
    if pyplot is None:
        return None
    totals = list(student_totals(verdicts).values())
    figure, axes = pyplot.subplots(figsize=(5, 2.6), dpi=100)
    axes.hist(totals, bins=[0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100.001], color="#5a8", edgecolor="#333")
    axes.set_xlabel("score (% of the points graded)")
    axes.set_ylabel("students")
    axes.set_xlim(0, 100)
    axes.yaxis.get_major_locator().set_params(integer=True)
    figure.tight_layout()
    figure.savefig(path)
    pyplot.close(figure)
    return path


def summary(verdicts: Sequence[Verdict], order: Sequence[Milestone]) -> List[str]:
    """The terminal's short view: a line per milestone, then the largest failure groups."""
    lines = ["%-18s %3d/%-3d passed  median %5.1f s" % (s.milestone.name, s.passed, s.graded, s.median_s)
             for s in milestone_stats(verdicts, order)]
    for g in failure_groups(verdicts)[:SUMMARY_GROUPS]:
        more = " ..." if len(g.students) > SUMMARY_STUDENTS else ""
        lines.append("%3d x %s: %s (%s%s)" % (len(g.students), g.milestone, g.label,
                                             ", ".join(g.students[:SUMMARY_STUDENTS]), more))
    return lines
