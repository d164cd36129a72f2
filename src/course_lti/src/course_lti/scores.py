"""A grading's output folder as the scores to post: pure, no network.

The grader writes `<out>/<student>/results.json` (course_grader.gradescope: `tests[]` with
`score`, `max_score`, `status`, `output` = "passed" or "FAILED: reason", then the log tails, and
`extra_data` with the milestone and the cause). Each line item (course_lti.config.line_item_groups)
gets, per student graded on it:

- per milestone: the milestone's points, its maximum, and its reason as the comment;
- per assignment: the sum of the points of its milestones the student was graded on, out of the
  sum of all its milestones' points (a milestone whose package the student did not hand in counts
  0 in the total), the comment one line per milestone.

What is not a grade is never posted, so nothing replaces an earlier grade with 0: a student with
no results.json (the hub could not snapshot them: `not-graded.csv`), a milestone the student was
not graded on (per milestone), a verdict the grader itself could not reach (interrupted, its own
error, the course's tools failing: `NO_GRADE_CAUSES`; per assignment, the whole assignment is
then held back).

The timestamp of a student's scores is the time their results.json was written: the same on
every re-post of one grading (an LMS keeps a score whose timestamp is not older than the one it
has), later after a regrade of that student.
"""
from __future__ import annotations

import csv
import datetime
import json
import os
from typing import Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple

RESULTS = "results.json"
NOT_GRADED = "not-graded.csv"  # the hub's: students whose files could not be snapshotted
GRADEBOOK = "gradebook.csv"
PASSED = "passed"
FAILED = "FAILED: "
# Causes (course_format.causes) of verdicts that say nothing about the student's work.
NO_GRADE_CAUSES = frozenset({"interrupted", "grader_error", "course_tools"})
COMMENT_LIMIT = 1000  # characters of a milestone's comment
REASON_LIMIT = 300  # characters of one milestone's reason inside an assignment's comment
ASSIGNMENT_COMMENT_LIMIT = 4000
LABEL_LIMIT = 100
CUT = " [...]"


class MilestoneInfo(NamedTuple):
    """What the course says of a milestone (course_format.milestone.Milestone's fields used here)."""

    name: str
    title: str
    points: float


class LineItem(NamedTuple):
    """A column of the LMS gradebook, found by resourceId and tag, created when missing."""

    resource_id: str  # the milestone's id, or the assignment's name
    label: str
    score_maximum: float
    tag: str

    def payload(self) -> Dict[str, object]:
        """The line item as POSTed (application/vnd.ims.lis.v2.lineitem+json)."""
        return {"scoreMaximum": self.score_maximum, "label": self.label, "resourceId": self.resource_id,
                "tag": self.tag}


class Verdict(NamedTuple):
    """One milestone's verdict as a student's results.json holds it."""

    milestone: str
    points: float
    maximum: float
    passed: bool
    reason: str  # "" when passed
    cause: str


class StudentScore(NamedTuple):
    """One score to post: a student on a line item."""

    student: str
    item: LineItem
    score_given: float
    score_maximum: float
    comment: str
    timestamp: str  # ISO 8601 with its time zone

    def payload(self, user_id: str) -> Dict[str, object]:
        """The score as POSTed to {lineitem}/scores (application/vnd.ims.lis.v1.score+json)."""
        return {"userId": user_id, "scoreGiven": self.score_given, "scoreMaximum": self.score_maximum,
                "comment": self.comment, "timestamp": self.timestamp, "activityProgress": "Completed",
                "gradingProgress": "FullyGraded"}


class Withheld(NamedTuple):
    """A score not computed: the student (or one of their verdicts) was not graded."""

    student: str
    resource_id: str  # "" for the whole student
    why: str


class Grading(NamedTuple):
    """What one grading folder gives to post."""

    scores: List[StudentScore]
    not_graded: Dict[str, str]  # student -> why no score at all is sent
    withheld: List[Withheld]  # verdicts that are no grade


def cut(text: str, limit: int) -> str:
    """`text` at most `limit` characters, a cut one ending in CUT."""
    return text if len(text) <= limit else text[:max(0, limit - len(CUT))].rstrip() + CUT


def reason_of(output: str) -> str:
    """The reason a results.json test's output gives: the text before the log tails."""
    text = output[len(FAILED):] if output.startswith(FAILED) else output
    return text.split("\n\n", 1)[0].strip()


def timestamp_of(path: str) -> str:
    """The time `path` was written, ISO 8601 in UTC to the millisecond."""
    when = datetime.datetime.fromtimestamp(os.stat(path).st_mtime, datetime.timezone.utc)
    return when.isoformat(timespec="milliseconds")


def read_results(path: str) -> List[Verdict]:
    """The verdicts of a results.json written by course_grader.gradescope (ValueError if it is not one)."""
    with open(path) as stream:
        data = json.load(stream)
    if not isinstance(data, dict) or not isinstance(data.get("tests"), list):
        raise ValueError("%s holds no tests[]" % path)
    found = []
    for test in data["tests"]:
        extra = test.get("extra_data") or {}
        name = extra.get("milestone") or str(test.get("name", "")).split(":", 1)[0]
        passed = test.get("status") == "passed"
        output = str(test.get("output", ""))
        found.append(Verdict(name, float(test.get("score", 0.0)), float(test.get("max_score", 0.0)), passed,
                             "" if passed else reason_of(output), str(extra.get("cause", ""))))
    return found


def students_of(out: str) -> List[str]:
    """The students of the grading in `out`: the gradebook's rows and every folder with a
    results.json (a row without one is a student the grading could not grade)."""
    try:
        with open(os.path.join(out, GRADEBOOK), newline="") as stream:
            rows = {row[0] for row in list(csv.reader(stream))[1:] if row}
    except OSError:
        rows = set()
    try:
        folders = {e for e in os.listdir(out) if not e.startswith("_") and os.path.isfile(os.path.join(out, e, RESULTS))}
    except OSError:
        folders = set()
    return sorted(rows | folders)


def not_graded_of(out: str) -> Dict[str, str]:
    """The hub's not-graded.csv in `out` (student -> why), {} without one."""
    try:
        with open(os.path.join(out, NOT_GRADED), newline="") as stream:
            return {row["student"]: row.get("reason", "") for row in csv.DictReader(stream) if row.get("student")}
    except (OSError, KeyError):
        return {}


def milestone_comment(verdict: Verdict) -> str:
    return PASSED if verdict.passed else cut("failed: " + verdict.reason, COMMENT_LIMIT)


def assignment_comment(members: Sequence[MilestoneInfo], graded: Mapping[str, Verdict]) -> str:
    lines = []
    for m in members:
        v = graded.get(m.name)
        if v is None:
            lines.append("%s: not handed in (0/%g)" % (m.name, m.points))
        elif v.passed:
            lines.append("%s: passed (%g/%g)" % (m.name, v.points, m.points))
        else:
            lines.append("%s: failed (%g/%g): %s" % (m.name, v.points, m.points, cut(v.reason, REASON_LIMIT)))
    return cut("\n".join(lines), ASSIGNMENT_COMMENT_LIMIT)


def line_items(groups: Mapping[str, Sequence[str]], course: Mapping[str, MilestoneInfo], tag: str,
               per_milestone: bool) -> Dict[str, LineItem]:
    """The line item of each group: its maximum the sum of its milestones' points."""
    items = {}
    for name, members in groups.items():
        label = "%s: %s" % (name, course[name].title) if per_milestone else name
        items[name] = LineItem(name, cut(label, LABEL_LIMIT), float(sum(course[m].points for m in members)), tag)
    return items


def student_scores(student: str, verdicts: Sequence[Verdict], timestamp: str, items: Mapping[str, LineItem],
                   groups: Mapping[str, Sequence[str]], course: Mapping[str, MilestoneInfo], per_milestone: bool
                   ) -> Tuple[List[StudentScore], List[Withheld]]:
    """One student's scores on every line item they were graded on, and what is held back."""
    by_name = {v.milestone: v for v in verdicts}
    scores, withheld = [], []
    for name, members in groups.items():
        graded = {m: by_name[m] for m in members if m in by_name}
        if not graded:
            continue  # nothing of this line item graded for them: no score at all
        no_grade = [v for v in graded.values() if v.cause in NO_GRADE_CAUSES]
        if no_grade:
            withheld.append(Withheld(student, name, "%s not graded (%s): regrade it" % (
                ", ".join(v.milestone for v in no_grade), ", ".join(sorted({v.cause for v in no_grade})))))
            continue
        item = items[name]
        if per_milestone:
            verdict = graded[name]
            comment = milestone_comment(verdict)
        else:
            comment = assignment_comment([course[m] for m in members], graded)
        given = float(sum(v.points for v in graded.values()))
        scores.append(StudentScore(student, item, given, item.score_maximum, comment, timestamp))
    return scores, withheld


def from_grading(out: str, groups: Mapping[str, Sequence[str]], course: Sequence[MilestoneInfo], tag: str,
                 per_milestone: bool, students: Optional[Sequence[str]] = None) -> Grading:
    """Every score the grading in `out` gives, for `students` (default: every student of it)."""
    info = {m.name: m for m in course}
    items = line_items(groups, info, tag, per_milestone)
    not_graded = not_graded_of(out)
    scores: List[StudentScore] = []
    withheld: List[Withheld] = []
    for student in students if students is not None else students_of(out):
        if student in not_graded:
            continue
        path = os.path.join(out, student, RESULTS)
        try:
            verdicts = read_results(path)
            stamp = timestamp_of(path)
        except (OSError, ValueError) as err:
            not_graded[student] = "no results: %s" % (getattr(err, "strerror", None) or err)
            continue
        mine, held = student_scores(student, verdicts, stamp, items, groups, info, per_milestone)
        scores += mine
        withheld += held
    return Grading(scores, not_graded, withheld)
