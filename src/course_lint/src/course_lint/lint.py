"""Grade a course's reference solution and its mutants, and give each mutant its status.

For a milestone, the reference is the packages of the course's reference solution that the
milestone names; each mutant is that reference with one file mutated (course_lint.mutants). They
are handed to `rosrun course_grader grade --course DIR --only MILESTONE` as students'
submissions, so they are built and run exactly as a student's would be: first the reference
alone, with course-lint's probe beside it (course_lint.ran), which measures what its run
executes; then, in one grader run, every mutant whose change did run. Each mutant ends with one
of four statuses:
- killed: the milestone fails it;
- survived: the milestone passes it: a mistake the check does not see;
- equivalent: it survived, and the course file says why no check can kill it
  (`equivalent: {NAME: REASON}`; an annotation that names no survivor is a problem of the course
  file, reported by the command);
- not run: what it changes never ran while the reference passed the milestone, so no check
  could see it; it is not graded.
The score is killed / (killed + survived).
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
from course_grader import cli as grader_cli
from course_format.milestone import Equivalent, Milestone

from course_lint import ran as measure
from course_lint import used_files
from course_lint.mutants import Mutant, Operator, package_mutants

REFERENCE = "reference"
# In each submission handed to the grader: the milestones it is graded on (the grader's --only-from).
ONLY_FILE = "course_lint_only.json"
RUNS_PER_CORE = 5  # the grader's runs at once, a core (default_jobs)
SHARED_BUILDS = 2  # submissions made ready at once (the grader's --builds)
GRADE = ["rosrun", "course_grader", "grade"]
LOG_TAIL_LINES = 20
STARTS = ("rosrun", "roslaunch")  # a start step's parameters naming what it starts
KILLED, SURVIVED, EQUIVALENT, NOT_RUN = "killed", "survived", "equivalent", "not run"
STATUSES = (KILLED, SURVIVED, EQUIVALENT, NOT_RUN)


class Outcome(NamedTuple):
    name: str  # "reference" or the mutant's "<operator>_<n>"
    mutant: Optional[Mutant]
    graded: bool
    passed: bool
    reason: str  # the grader's reason for a failure, or why it was not graded
    status: str = ""  # a mutant's: one of STATUSES ("" when not graded: --list)
    why: str = ""  # not run: what never ran; equivalent: the course file's reason


class MilestoneLint(NamedTuple):
    milestone: Milestone
    reference: Outcome
    mutants: List[Outcome]
    notes: List[str]
    problems: Tuple[Tuple[Equivalent, str], ...] = ()  # annotations that name no survivor, and why
    measured: Tuple[Tuple[str, str], ...] = ()  # (kind of file, "measured" or why not) for not run

    def having(self, status: str) -> List[Outcome]:
        return [o for o in self.mutants if o.status == status]

    @property
    def killed(self) -> List[Outcome]:
        return self.having(KILLED)

    @property
    def survivors(self) -> List[Outcome]:
        return self.having(SURVIVED)

    @property
    def scored(self) -> int:
        """The score's denominator: killed + survived."""
        return len(self.killed) + len(self.survivors)

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


def lay_out(sub: str, milestone: Milestone, folders: Dict[str, str], mutant: Optional[Mutant],
            graded_on: Sequence[str]) -> str:
    """`sub/<package folder>/...`: the milestone's packages of the reference, with the mutant's
    change (None: the reference), and ONLY_FILE naming the milestones it is graded on."""
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
    with open(os.path.join(sub, ONLY_FILE), "w") as f:
        json.dump({name: "course-lint" for name in graded_on}, f)
    return sub


def default_jobs() -> int:
    """The grader's runs at once for a lint: RUNS_PER_CORE a core, as many as the memory holds.
    More than a class's grading (course_grader.cli.RUNS_PER_CORE): most runs of a lint are a
    mutant's that its check fails by waiting out a time-out or a key's answer, with the CPU idle
    (the built-in course at 10 runs on 2 cores kept 60% of them busy)."""
    return grader_cli.default_jobs(grader_cli.CORES, grader_cli.available_mib(), RUNS_PER_CORE)


def grade(course: Course, subs: Sequence[str], out: str, jobs: Optional[int]) -> Tuple[int, str]:
    """Run the grader on the submissions, each graded on the milestones its ONLY_FILE names; its
    exit code and its log's path. Most submissions are copies of a build (--share-builds), which
    take a second each, not a catkin_make: SHARED_BUILDS of them are made ready at once."""
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    log = os.path.join(out, "grade.log")
    command = GRADE + ["--course", course.root, "--only-from", ONLY_FILE, "--share-builds", "--out", out,
                       "--jobs", str(jobs or default_jobs()), "--builds", str(SHARED_BUILDS)]
    command += list(subs)
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


def outcome_of(name: str, mutant: Optional[Mutant], out: str, sub: str, milestone: str) -> Outcome:
    """The outcome of a graded submission; a mutant's status killed or survived (also when the
    grader gave no verdict: a mistake not shown to be seen)."""
    done, passed, reason = verdict(out, os.path.basename(sub), milestone)
    status = "" if mutant is None else KILLED if done and not passed else SURVIVED
    return Outcome(name, mutant, done, passed, reason, status)


def what_became(outcome: Outcome) -> str:
    """A mutant that is no survivor, in words, for an annotation that names it."""
    if outcome.status == KILLED:
        return "%s is killed (%s)" % (outcome.name, (outcome.reason.splitlines() or [""])[0][:160])
    if outcome.status == NOT_RUN:
        return "%s is not run (%s): it needs no annotation" % (outcome.name, outcome.why)
    return "%s got no verdict from the grader (%s)" % (outcome.name, outcome.reason[:160])


def annotated(milestone: Milestone, outcomes: Sequence[Outcome], operators: Sequence[Operator]
              ) -> Tuple[List[Outcome], List[Tuple[Equivalent, str]]]:
    """The outcomes with each survivor the milestone's `equivalent` names made equivalent, and the
    annotations that name no surviving mutant with why. Annotations of operators this run left out
    (--operators) are passed over."""
    linted = {op.name for op in operators}
    index = {o.name: i for i, o in enumerate(outcomes)}
    result = list(outcomes)
    problems = []
    for annotation in milestone.equivalent:
        if annotation.mutant.rsplit("_", 1)[0] not in linted:
            continue
        i = index.get(annotation.mutant)
        if i is None:
            problems.append((annotation, "names no mutant of this milestone (its mutants: %s)"
                             % (", ".join(o.name for o in outcomes) or "none")))
        elif result[i].status == SURVIVED and result[i].graded:
            result[i] = result[i]._replace(status=EQUIVALENT, why=annotation.reason)
        else:
            problems.append((annotation, "names no surviving mutant: %s" % what_became(result[i])))
    return result, problems


class Plan(NamedTuple):
    """A milestone's mutants before grading, with what the reference's run left not run."""
    milestone: Milestone
    folders: Dict[str, str]  # package name -> the reference's folder
    mutants: List[Tuple[str, Mutant]]
    notes: List[str]
    missing: str = ""  # why the milestone cannot be linted (its packages are not in the reference)


def plan(course: Course, milestone: Milestone, operators: Sequence[Operator]) -> Plan:
    folders = reference_packages(course.solution)
    missing = [p for p in milestone.packages if p not in folders]
    if missing:
        why = ("the reference solution (%s) holds no package %s" % (course.solution, ", ".join(missing))
               if course.solution else "the course has no reference solution folder (course.yaml's solution)")
        return Plan(milestone, folders, [], [], why)
    mutants, notes = milestone_mutants(milestone, folders, operators)
    return Plan(milestone, folders, mutants, notes)


def shared_key(p: Plan, mutant: Mutant) -> Tuple:
    """Mutants of several milestones with the same key are one submission, built and graded once on
    each of them: the same packages, the same file changed the same way."""
    return (tuple(sorted(p.milestone.packages)), mutant.package, mutant.path, mutant.text)


def lint_course(course: Course, milestones: Sequence[Milestone], work: str, jobs: Optional[int],
                operators: Sequence[Operator], grading: bool = True, probe: bool = True) -> List[MilestoneLint]:
    """Each milestone's reference and mutant outcomes (with grading False: the mutants, none graded).

    Two grader runs for the whole course, every submission in them graded on its own milestones
    (ONLY_FILE), so the machine's cores stay busy across milestones: with `probe`, every
    milestone's reference first, each with course-lint's probe (course_lint.ran); then every mutant
    whose change did run, a mutant shared by several milestones (shared_key) built and run once for
    all of them, with the references that failed with the probe. Without `probe`, the references and
    every mutant in one run, as before the statuses (none is not run)."""
    plans = [plan(course, m, operators) for m in milestones]
    if not grading:
        return [MilestoneLint(p.milestone, Outcome(REFERENCE, None, False, False, p.missing or "not graded"),
                              [Outcome(name, m, False, False, "not graded") for name, m in p.mutants], p.notes)
                for p in plans]
    base, grades = os.path.join(work, "submissions"), os.path.join(work, "grades")
    references: Dict[str, Outcome] = {}
    why_not_run: Dict[Tuple[str, str], str] = {}
    kinds: Dict[str, Dict[str, str]] = {}
    probed = [p for p in plans if not p.missing and probe and
              any(os.path.basename(m.path) != used_files.CMAKE for _, m in p.mutants)]  # the build always runs
    if probed:
        subs = []
        for p in probed:
            sub = lay_out(os.path.join(base, "%s__%s" % (p.milestone.name, REFERENCE)), p.milestone, p.folders,
                          None, [p.milestone.name])
            measure.lay_out(sub)
            subs.append(sub)
        say("grading the reference of %d milestone(s), measuring what each runs ..." % len(probed))
        out = run_grader(course, subs, os.path.join(grades, REFERENCE), jobs, [p.notes for p in probed])
        for p, sub in zip(probed, subs):
            outcome = outcome_of(REFERENCE, None, out, sub, p.milestone.name)
            if outcome.graded and outcome.passed:
                references[p.milestone.name] = outcome
                ran = measure.read(measure.workspace(out, os.path.basename(sub)))
                p.notes.extend(ran.notes())
                kinds[p.milestone.name] = measure.kinds_measured(ran)
                for name, m in p.mutants:
                    why_not_run[(p.milestone.name, name)] = not_run_of(m, p.folders, p.milestone, ran)
            else:
                p.notes.append("the reference failed with course-lint's probe beside it (%s): graded again without "
                               "it, and every mutant graded" % (outcome.reason.splitlines() or [""])[0][:200])
    # The second run: one submission per shared key (and per reference to grade), with its milestones.
    groups: Dict[Tuple, List[Tuple[Plan, str, Optional[Mutant]]]] = {}
    for p in plans:
        if p.missing:
            continue
        if p.milestone.name not in references:
            groups[(REFERENCE, p.milestone.name)] = [(p, REFERENCE, None)]
        for name, m in p.mutants:
            if not why_not_run.get((p.milestone.name, name)):
                groups.setdefault(shared_key(p, m), []).append((p, name, m))
    outcomes: Dict[Tuple[str, str], Outcome] = {}
    if groups:
        subs = []
        for members in groups.values():
            first, name, mutant = members[0]
            subs.append(lay_out(os.path.join(base, "%s__%s" % (first.milestone.name, name)), first.milestone,
                                first.folders, mutant, [p.milestone.name for p, _, _ in members]))
        graded = sum(len(members) for members in groups.values())
        say("grading %d mutant(s) of %d milestone(s) in %d submission(s) (%d not run) ..." % (
            graded - sum(1 for key in groups if key[0] == REFERENCE), len(plans), len(subs),
            sum(1 for why in why_not_run.values() if why)))
        involved = [p.notes for p in plans if not p.missing]
        out = run_grader(course, subs, os.path.join(grades, "mutants"), jobs, involved)
        for members, sub in zip(groups.values(), subs):
            for p, name, m in members:
                outcomes[(p.milestone.name, name)] = outcome_of(name, m, out, sub, p.milestone.name)
    results = []
    for p in plans:
        if p.missing:
            results.append(MilestoneLint(p.milestone, Outcome(REFERENCE, None, False, False, p.missing), [], p.notes))
            continue
        key = p.milestone.name
        reference = references.get(key) or outcomes[(key, REFERENCE)]
        found = [outcomes[(key, name)] if (key, name) in outcomes else
                 Outcome(name, m, False, False, "not graded: not run", NOT_RUN, why_not_run[(key, name)])
                 for name, m in p.mutants]
        found, problems = annotated(p.milestone, found, operators)
        results.append(MilestoneLint(p.milestone, reference, found, p.notes, tuple(problems),
                                     tuple(sorted(kinds.get(key, {}).items()))))
    return results


def not_run_of(mutant: Mutant, folders: Dict[str, str], milestone: Milestone, ran: measure.Ran) -> str:
    """measure.not_run for one mutant, given the reference's files."""
    package = next((name for name in milestone.packages
                    if os.path.basename(folders.get(name, "")) == mutant.package), mutant.package)
    folder = folders.get(package, "")
    try:
        with open(os.path.join(folder, mutant.path), encoding="utf-8") as f:
            reference = f.read()
    except (OSError, UnicodeDecodeError):
        return ""
    try:
        with open(os.path.join(folder, used_files.CMAKE), encoding="utf-8") as f:
            cmake = f.read()
    except (OSError, UnicodeDecodeError):
        cmake = ""
    return measure.not_run(mutant, reference, ran, package, cmake)


def say(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


def run_grader(course: Course, subs: Sequence[str], out: str, jobs: Optional[int], notes: Sequence[List[str]]) -> str:
    """Grade the submissions into `out`; a note in each of `notes` when the grader exits other than 0.
    Returns `out`."""
    code, log = grade(course, subs, out, jobs)
    if code != 0:
        for each in notes:
            each.append("the grader exited %d (log: %s):\n%s" % (code, log, log_tail(log)))
    return out
