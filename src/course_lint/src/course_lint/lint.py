"""Grade a course's reference solution and its mutants, one grader run per milestone.

For a milestone, the reference is the packages of the course's reference solution that the
milestone names; each mutant is that reference with one file mutated (course_lint.mutants). All
of them are handed to `rosrun course_grader grade --course DIR --only MILESTONE` as students'
submissions, so they are built and run exactly as a student's would be. A mutant is killed when
the milestone fails for it; a survivor is a mistake the milestone's check does not see.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from typing import Dict, List, NamedTuple, Optional, Sequence, Set, Tuple

from catkin_pkg.packages import find_packages
from course_format.course_file import Course
from course_format.milestone import Milestone

from course_lint import used_files
from course_lint.mutants import Mutant, Operator, package_mutants

REFERENCE = "reference"
GRADE = ["rosrun", "course_grader", "grade"]
LOG_TAIL_LINES = 20
STARTS = ("rosrun", "roslaunch")  # a start step's parameters naming what it starts


class Outcome(NamedTuple):
    name: str  # "reference" or the mutant's "<operator>_<n>"
    mutant: Optional[Mutant]
    graded: bool
    passed: bool
    reason: str  # the grader's reason for a failure, or why it was not graded


class MilestoneLint(NamedTuple):
    milestone: Milestone
    reference: Outcome
    mutants: List[Outcome]
    notes: List[str]

    @property
    def killed(self) -> List[Outcome]:
        return [o for o in self.mutants if o.graded and not o.passed]

    @property
    def survivors(self) -> List[Outcome]:
        return [o for o in self.mutants if not (o.graded and not o.passed)]

    @property
    def reference_fails(self) -> bool:
        return not (self.reference.graded and self.reference.passed)


def reference_packages(solution: Optional[str]) -> Dict[str, str]:
    """Package name -> its folder, for every catkin package in the reference solution."""
    if not solution or not os.path.isdir(solution):
        return {}
    return {pkg.name: os.path.join(solution, rel) for rel, pkg in find_packages(solution).items()}


def numbered(mutants: Sequence[Mutant]) -> List[Tuple[str, Mutant]]:
    """Each mutant's name in its milestone: "<operator>_<n>", n counting from 1 per operator."""
    counts: Dict[str, int] = {}
    named = []
    for mutant in mutants:
        counts[mutant.operator.name] = counts.get(mutant.operator.name, 0) + 1
        named.append(("%s_%d" % (mutant.operator.name, counts[mutant.operator.name]), mutant))
    return named


def step_names(milestone: Milestone) -> Set[str]:
    """What a data milestone's steps start: the script, executable or launch file of each
    `rosrun: PKG NAME` and `roslaunch: PKG FILE` (empty for a Python check's milestone)."""
    found = set()
    for step in milestone.steps:
        for key in STARTS:
            command = step.params.get(key)
            if isinstance(command, str) and command.split()[1:]:
                found.add(command.split()[1].rsplit("/", 1)[-1])
    if milestone.steps and not found:  # it starts nothing (e.g. only `generated`): only the build is its
        found.add(used_files.CMAKE)
    return found


def names_own_types(milestone: Milestone, package: str) -> bool:
    """Whether a data milestone's steps name a message, service or action of `package` (PKG/Name):
    a file left out of its build can only be seen by one that does."""
    def strings(value) -> List[str]:
        if isinstance(value, str):
            return [value]
        if isinstance(value, dict):
            return [s for k, v in value.items() for s in strings(k) + strings(v)]
        if isinstance(value, (list, tuple)):
            return [s for v in value for s in strings(v)]
        return []
    return any(s.startswith(package + "/") for step in milestone.steps for s in strings(step.params))


def milestone_mutants(milestone: Milestone, folders: Dict[str, str], operators: Sequence[Operator]
                      ) -> Tuple[List[Tuple[str, Mutant]], List[str]]:
    found, notes = [], []
    for package in milestone.packages:
        if package in folders:
            mine, why = package_mutants(folders[package], operators, names=step_names(milestone), package=package)
            if milestone.steps and not names_own_types(milestone, package):
                mine = [m for m in mine if m.operator.name != "msg_left_out"]
            found += mine
            notes += why
    order = {op.name: i for i, op in enumerate(operators)}
    return numbered(sorted(found, key=lambda m: order[m.operator.name])), notes


def lay_out(base: str, milestone: Milestone, folders: Dict[str, str],
            mutants: Sequence[Tuple[str, Mutant]]) -> List[str]:
    """`base/<milestone>__<name>/<package folder>/...` for the reference and each mutant."""
    subs = []
    for name, mutant in [(REFERENCE, None)] + list(mutants):
        sub = os.path.join(base, "%s__%s" % (milestone.name, name))
        shutil.rmtree(sub, ignore_errors=True)  # an earlier run's, kept with --keep
        for package in milestone.packages:
            folder = folders[package]
            shutil.copytree(folder, os.path.join(sub, os.path.basename(folder)), symlinks=True)
        if mutant is not None:
            path = os.path.join(sub, mutant.package, mutant.path)
            mode = os.stat(path).st_mode
            with open(path, "w", encoding="utf-8") as f:
                f.write(mutant.text)
            os.chmod(path, mode)
        subs.append(sub)
    return subs


def grade(course: Course, milestone: Milestone, subs: Sequence[str], out: str, jobs: int) -> Tuple[int, str]:
    """Run the grader on the submissions; its exit code and its log's path."""
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    log = os.path.join(out, "grade.log")
    command = GRADE + ["--course", course.root, "--only", milestone.name, "--jobs", str(jobs),
                       "--out", out] + list(subs)
    with open(log, "w") as f:
        code = subprocess.call(command, stdout=f, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    return code, log


def verdict(out: str, student: str, milestone: str) -> Tuple[bool, bool, str]:
    """(graded, passed, reason) of one submission's milestone, from its results.json."""
    try:
        with open(os.path.join(out, student, "results.json")) as f:
            tests = json.load(f).get("tests", [])
    except (OSError, ValueError) as err:
        return False, False, "not graded: no results.json (%s)" % err
    for test in tests:
        name = (test.get("extra_data") or {}).get("milestone") or str(test.get("name", "")).split(":", 1)[0]
        if name == milestone:
            passed = test.get("status") == "passed"
            return True, passed, "" if passed else str(test.get("output", "")).strip()
    return False, False, "not graded: results.json has no verdict for %s" % milestone


def log_tail(log: str) -> str:
    try:
        with open(log, errors="replace") as f:
            return "".join(f.readlines()[-LOG_TAIL_LINES:])
    except OSError:
        return ""


def lint_milestone(course: Course, milestone: Milestone, work: str, jobs: int,
                   operators: Sequence[Operator], grading: bool = True) -> MilestoneLint:
    """The reference's and every mutant's outcome (with grading False: the mutants, none graded)."""
    folders = reference_packages(course.solution)
    missing = [p for p in milestone.packages if p not in folders]
    if missing:
        why = ("the reference solution (%s) holds no package %s" % (course.solution, ", ".join(missing))
               if course.solution else "the course has no reference solution folder (course.yaml's solution)")
        return MilestoneLint(milestone, Outcome(REFERENCE, None, False, False, why), [], [])
    mutants, notes = milestone_mutants(milestone, folders, operators)
    if not grading:
        return MilestoneLint(milestone, Outcome(REFERENCE, None, False, False, "not graded"),
                             [Outcome(name, m, False, False, "not graded") for name, m in mutants], notes)
    subs = lay_out(os.path.join(work, "submissions"), milestone, folders, mutants)
    out = os.path.join(work, "grades", milestone.name)
    print("%s: grading the reference and %d mutant(s) ..." % (milestone.name, len(mutants)), file=sys.stderr, flush=True)
    code, log = grade(course, milestone, subs, out, jobs)
    if code != 0:
        notes.append("the grader exited %d (log: %s):\n%s" % (code, log, log_tail(log)))
    outcomes = [Outcome(name, mutant, *verdict(out, os.path.basename(sub), milestone.name))
                for (name, mutant), sub in zip([(REFERENCE, None)] + mutants, subs)]
    return MilestoneLint(milestone, outcomes[0], outcomes[1:], notes)
