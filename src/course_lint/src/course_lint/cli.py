"""course-lint DIR [--only M ...] [--jobs J] [--operators a,b] [--mutmut] [--grade-all] [--keep DIR] [--list] [--json FILE]

Shows that a course's checks can fail: grades each milestone of the course in DIR (a folder with a
course.yaml) against the course's reference solution and against mutants of it, the reference
with one mistake each (docs/course_lint.md lists the operators). Each mutant is killed, survived
(a mistake the milestone's check does not catch), equivalent (a survivor the course file says no
check can kill, `equivalent: {NAME: REASON}`) or not run (what it changes never ran while the
reference passed: not graded). Per milestone it prints K/N, killed over killed and survived, and
names the others. Exit code: 2 when the course file has an error (an `equivalent` annotation that
names no surviving mutant among them), else 1 when a reference fails its milestone, else 0. The
last line is `mutants killed K/N`.
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import tempfile
from typing import Dict, List, Optional

from course_format import course_file

from course_lint import generic
from course_lint.lint import EQUIVALENT, NOT_RUN, STATUSES, MilestoneLint, Outcome, lint_course
from course_lint.mutants import OPERATORS, by_names

EXIT_REFERENCE_FAILS = 1
EXIT_COURSE_ERROR = 2


def parse(argv: Optional[List[str]]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="course-lint", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("course", metavar="DIR", help="the course folder (holding course.yaml)")
    parser.add_argument("--only", action="append", metavar="M", help="lint only milestone M (repeatable)")
    parser.add_argument("--jobs", "-j", type=int, help="the grader's runs at once (default: 5 per core, as the "
                                                       "memory allows)")
    parser.add_argument("--operators", metavar="A,B", help="only these mutant operators (default: all, see --list)")
    parser.add_argument("--keep", metavar="DIR", help="keep the mutants' folders and the grader's output in DIR")
    parser.add_argument("--mutmut", action="store_true",
                        help='also generic Python mutants from mutmut 2 (pip install "mutmut<3")')
    parser.add_argument("--grade-all", action="store_true",
                        help="grade every mutant, measuring nothing of the reference's run (no mutant is not run)")
    parser.add_argument("--list", action="store_true", help="print the mutants without grading them")
    parser.add_argument("--json", metavar="FILE", help="also write the table as JSON to FILE")
    return parser.parse_args(argv)


def where(outcome: Outcome) -> str:
    m = outcome.mutant
    return "%s/%s:%d" % (m.package, m.path, m.line) if m else ""


def survivor(outcome: Outcome) -> str:
    graded = "" if outcome.graded else "; not graded"
    return "%s (%s, %s%s)" % (outcome.name, outcome.mutant.operator.description, where(outcome), graded)


def explained(outcome: Outcome) -> str:
    """An equivalent or not-run mutant: its name, where, and why (the course file's reason, or what never ran)."""
    return "%s (%s: %s)" % (outcome.name, where(outcome), outcome.why)


def milestone_line(result: MilestoneLint) -> str:
    """NAME  K/N killed  survivors: ...  equivalent: ...  not run: ... (N: killed and survived)."""
    head = "%s  %s%d/%d killed" % (result.milestone.name, "REFERENCE FAILS  " if result.reference_fails else "",
                                   len(result.killed), result.scored)
    return "%s  survivors: %s  equivalent: %s  not run: %s" % (
        head, ", ".join(survivor(o) for o in result.survivors) or "none",
        ", ".join(explained(o) for o in result.having(EQUIVALENT)) or "none",
        ", ".join(explained(o) for o in result.having(NOT_RUN)) or "none")


def listing(result: MilestoneLint) -> List[str]:
    reasons = {e.mutant: e.reason for e in result.milestone.equivalent}
    lines = ["%s  %d mutant(s)" % (result.milestone.name, len(result.mutants))]
    lines += ["  %-18s %-40s %s%s" % (o.name, where(o), o.mutant.changed[:80],
                                      "  (equivalent: %s)" % reasons[o.name] if o.name in reasons else "")
              for o in result.mutants]
    return lines


def counts(results: List[MilestoneLint]) -> Dict[str, int]:
    """Mutants per status over the milestones."""
    return {status: sum(len(r.having(status)) for r in results) for status in STATUSES}


def summary(results: List[MilestoneLint]) -> str:
    """The line before the last: every mutant made, by status."""
    found = counts(results)
    return "mutants: %d made, %d killed, %d survived, %d equivalent, %d not run" % (
        sum(len(r.mutants) for r in results), found["killed"], found["survived"], found["equivalent"],
        found["not run"])


def shown(path: str) -> str:
    """A course file's path as the loader shows it: relative when below the current folder."""
    rel = os.path.relpath(path)
    return path if rel.startswith(os.pardir) else rel


def problems(course: course_file.Course, results: List[MilestoneLint]) -> List[str]:
    """`FILE:LINE: milestones[i].equivalent.NAME: why` for each annotation that names no survivor."""
    index = {m.name: i for i, m in enumerate(course.milestones)}
    return ["%s:%d: milestones[%d].equivalent.%s: %s" % (shown(r.milestone.course_file or course.file), e.line,
                                                          index[r.milestone.name], e.mutant, why)
            for r in results for e, why in r.problems]


def as_json(course: course_file.Course, results: List[MilestoneLint]) -> Dict:
    def outcome(o: Outcome) -> Dict:
        entry = {"name": o.name, "graded": o.graded, "passed": o.passed, "reason": o.reason}
        if o.mutant:
            entry.update(operator=o.mutant.operator.name, description=o.mutant.operator.description,
                         file="%s/%s" % (o.mutant.package, o.mutant.path), line=o.mutant.line,
                         changed=o.mutant.changed, status=o.status, why=o.why, killed=o.status == "killed")
        return entry

    def by_status(found: Dict[str, int]) -> Dict[str, int]:
        return {status.replace(" ", "_"): n for status, n in found.items()}
    return dict({"course": course.name, "root": course.root,
                 "milestones": [dict({"name": r.milestone.name, "title": r.milestone.title,
                                      "packages": list(r.milestone.packages), "reference": outcome(r.reference),
                                      "reference_fails": r.reference_fails, "total": r.scored,
                                      "made": len(r.mutants), "measured": dict(r.measured),
                                      "mutants": [outcome(o) for o in r.mutants], "notes": r.notes,
                                      "problems": ["%s: %s" % (e.mutant, why) for e, why in r.problems]},
                                     **by_status(counts([r]))) for r in results],
                 "total": sum(r.scored for r in results), "made": sum(len(r.mutants) for r in results),
                 "problems": problems(course, results)},
                **by_status(counts(results)))


def main(argv: Optional[List[str]] = None) -> int:
    opts = parse(argv)
    try:
        course = course_file.load(opts.course)
    except course_file.CourseError as err:
        print(err, file=sys.stderr)
        return EXIT_COURSE_ERROR
    try:
        operators = by_names(opts.operators.split(",")) if opts.operators else OPERATORS
        operators += (generic.operator(),) if opts.mutmut else ()
    except (ValueError, generic.Unavailable) as err:
        print(err, file=sys.stderr)
        return EXIT_COURSE_ERROR
    names = [m.name for m in course.milestones]
    unknown = sorted(set(opts.only or []) - set(names))
    if unknown:
        print("%s has no milestone %s (it has: %s)" % (course.file, ", ".join(unknown), ", ".join(names)), file=sys.stderr)
        return EXIT_COURSE_ERROR
    work = os.path.abspath(opts.keep) if opts.keep else tempfile.mkdtemp(prefix="course-lint-")
    if not opts.keep:
        os.chmod(work, 0o755)  # the grader's sandbox user reads the mutants and writes below
    chosen = [m for m in course.milestones if not opts.only or m.name in opts.only]
    try:
        results = lint_course(course, [m for m in chosen if m.packages], work, opts.jobs, operators,
                              grading=not opts.list, probe=not opts.grade_all)
        linted = {r.milestone.name: r for r in results}
        for milestone in chosen:  # in the course's order
            result = linted.get(milestone.name)
            if result is None:
                print("%s  not linted: it names no package (it checks the course workspace)" % milestone.name)
                continue
            print("\n".join(listing(result)) if opts.list else milestone_line(result), flush=True)
            if result.reference_fails and not opts.list:
                print("  the reference fails %s: %s" % (result.milestone.name, result.reference.reason), flush=True)
            for note in result.notes:
                print("  note: %s" % note)
    finally:
        if not opts.keep:
            shutil.rmtree(work, ignore_errors=True)
    if opts.json:
        with open(opts.json, "w") as f:
            json.dump(as_json(course, results), f, indent=2)
    if opts.list:
        print("mutants listed %d" % sum(len(r.mutants) for r in results))
        return 0
    wrong = problems(course, results)
    for problem in wrong:
        print(problem, file=sys.stderr)
    print(summary(results))
    print("mutants killed %d/%d" % (sum(len(r.killed) for r in results), sum(r.scored for r in results)))
    if wrong:
        return EXIT_COURSE_ERROR
    return EXIT_REFERENCE_FAILS if any(r.reference_fails for r in results) else 0
