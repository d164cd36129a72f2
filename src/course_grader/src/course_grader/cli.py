"""rosrun course_grader grade [SUBMISSION...] [--class DIR] [--course DIR] [--jobs N] [--only M ...]
                             [--out DIR] [--boilerplate DIR ...] [--regrade STUDENT]
                             [--lti CONFIG --lti-users FILE [--post-only] [--dry-run]]

Grades each SUBMISSION (a folder, .zip or .tar.gz of catkin packages), or every entry of a class
folder (--class DIR), against the milestones of a course (--course DIR: a folder with a
course.yaml, docs/course_format.md; default the built-in course, courses/robotics_labs); with
neither, grades the course's own reference solution (every milestone; for the built-in course
the checkout's solutions/ folder, built and run as an overlay like a student's). The grader runs in the course workspace's environment alone: started
from another (the reference overlay sourced), it starts itself again in the course's.
Writes under --out (default ./grades):
  <student>/<milestone>/junit.xml, *.log, *.png   verdict, student logs, canvas snapshots
  <student>/results.json                          Gradescope results
  gradebook.csv, report.html                      the class
  milestones.csv, failure_groups.csv, scores.png  the class at a glance (per milestone, failures by cause)
  similarity.csv                                  pairs of submissions too alike (never part of a verdict)
--regrade STUDENT grades that one student again into an existing --out (their submission among
those given, else the copy the last grading unpacked) and writes the class files again; every
other student's verdicts stay as their results.json holds them.
--lti CONFIG posts each student's scores to the LMS gradebook after the grading (LTI 1.3 AGS,
course_lti; CONFIG is lti.yaml, --lti-users FILE maps each student to their LMS user id: a CSV
student,user_id, or the hub's lti-users.json); --post-only posts the grading already in --out and
grades nothing (also: what an earlier run left pending, lti-pending.json); --dry-run prints the
requests it would send and sends nothing. docs/grading.md, "Grades back to the LMS".
Prints a line per finished submission. Exit code: with the reference, 1 if a milestone fails;
with students, 0 once every submission has its verdicts; 2 on a bad command line, course file or
LTI configuration (checked before grading); 3 when, with --lti, some score could not be posted
(listed in <out>/lti-pending.json); 130 when stopped by Ctrl+C (SIGINT) or
SIGTERM: within seconds, the runs under way ended, the verdicts so far written and the rest
"not graded (interrupted)". Each start first ends what a killed grading left (processes, pids
cgroups; in the same --out, its work folders).
"""
from __future__ import annotations

import argparse
import os
import shutil
import signal
import sys
import tempfile
import time
from typing import List, Optional, Sequence, Set, Tuple

from course_format import course_file
from course_format.milestone import Milestone
from course_lti import post as lti_post
from course_lti.config import ConfigError
from course_sandbox import leftovers, levels
from course_sandbox.policy import Limits, MiB

from course_grader import class_outputs, class_view, submissions, workspace
from course_grader.verdict import INTERRUPTED
from course_grader.runner import REFERENCE, Busy, Grader, Options, claim_output, release_output

# Three milestone runs per core: most of a run is waiting on behaviour the text fixes (a drawing,
# a robot driving, a time-out), which other runs' CPU work fills. Reference, 18 milestones on 2
# cores: --jobs 3 45-47 s, --jobs 6 26 s (docs/benchmarks.md "Where a grading's time goes").
RUNS_PER_CORE = 3
# Memory a run may take: its processes' RSS summed peaked at 373 MiB (turtlebot, MuJoCo), 286 MiB
# (launch_params); a small container (Gradescope's default) gets fewer runs at once.
MIB_PER_RUN = 400


def available_mib(meminfo: str = "/proc/meminfo", cgroup: str = "/sys/fs/cgroup") -> float:
    """Memory this process may still use: MemAvailable, or less under a cgroup v2 limit."""
    available = float("inf")
    try:
        with open(meminfo) as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    available = int(line.split()[1]) / 1024
    except (OSError, ValueError):
        pass
    try:
        with open(os.path.join(cgroup, "memory.max")) as f:
            limit = f.read().strip()
        with open(os.path.join(cgroup, "memory.current")) as f:
            used = int(f.read().strip())
        if limit != "max":
            available = min(available, (int(limit) - used) / 2 ** 20)
    except (OSError, ValueError):
        pass
    return available


def default_jobs(cores: int, memory_mib: float, per_core: int = RUNS_PER_CORE) -> int:
    """`per_core` runs per core (RUNS_PER_CORE), as many as the memory holds, at least one."""
    return max(1, min(per_core * cores, int(memory_mib // MIB_PER_RUN)))


CORES = len(os.sched_getaffinity(0))
DEFAULT_JOBS = default_jobs(CORES, available_mib())
# Submissions built at once, beside the runs: a build (catkin_make) keeps about one core busy.
DEFAULT_BUILDS = max(1, CORES // 2)
# Runs started while a submission builds, when no run is under way (course_grader.early_runs): CMake
# configures on one core, so the start-ups of that many runs fill the others.
DEFAULT_EARLY = max(1, CORES - DEFAULT_BUILDS)


def parse(argv: Optional[List[str]]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="grade", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("submissions", nargs="*", help="folders, .zip or .tar.gz files, one per student")
    parser.add_argument("--class", dest="class_dir", help="a folder whose every entry is one submission")
    parser.add_argument("--jobs", "-j", type=int, default=DEFAULT_JOBS,
                        help="milestone runs at once, across submissions (default %(default)s)")
    parser.add_argument("--builds", type=int, default=DEFAULT_BUILDS,
                        help="submissions built at once, beside the runs (default %(default)s)")
    parser.add_argument("--early", type=int, default=DEFAULT_EARLY,
                        help="runs started while a submission builds, if no run is under way; their checks "
                             "wait until the build is done (default %(default)s, 0: none)")
    parser.add_argument("--share-builds", action="store_true",
                        help="build once the submissions whose build inputs are the same (they differ only in "
                             "Python and launch files), the others getting a copy: course-lint's mutants of "
                             "one reference; never for a class (course_grader.shared_builds)")
    parser.add_argument("--only", action="extend", nargs="+", metavar="M",
                        help="grade only these milestones (--only a b, or --only a --only b)")
    parser.add_argument("--only-from", metavar="FILE",
                        help="grade each submission on the milestones named (as keys) in its own JSON FILE")
    parser.add_argument("--out", default="grades", help="output folder (default ./grades)")
    parser.add_argument("--timeout", type=float, default=240.0, help="time limit per milestone run, s")
    parser.add_argument("--disk", type=int, default=Limits().disk_bytes // MiB, metavar="MIB",
                        help="disk one student's build and runs may fill in total, MiB (default %(default)s)")
    parser.add_argument("--results-json", metavar="PATH",
                        help="also write the (one) submission's Gradescope results.json to PATH")
    parser.add_argument("--boilerplate", action="append", default=[], metavar="DIR",
                        help="code every student was given (a template): left out of the similarity check")
    parser.add_argument("--regrade", metavar="STUDENT",
                        help="grade only STUDENT again, into the earlier grading in --out (see above)")
    parser.add_argument("--course", metavar="DIR", default="",
                        help="the course: a folder holding course.yaml (default: the built-in course)")
    parser.add_argument("--lti", metavar="CONFIG", default="",
                        help="post the scores to the LMS gradebook (LTI 1.3 AGS) as CONFIG (lti.yaml) says")
    parser.add_argument("--lti-users", metavar="FILE", default="",
                        help="with --lti: each student's LMS user id (CSV student,user_id, or the hub's lti-users.json)")
    parser.add_argument("--post-only", action="store_true",
                        help="with --lti: post the grading already in --out (and what it left pending); grade nothing")
    parser.add_argument("--dry-run", action="store_true",
                        help="with --lti: print the requests that would be sent to the LMS, send nothing")
    parser.add_argument("--list", action="store_true", help="list the milestones and exit")
    parser.add_argument("-v", "--verbose", action="store_true", help="a line per milestone run too")
    return parser.parse_args(argv)


def split_only(only: Optional[List[str]], names: Set[str]) -> Tuple[Optional[List[str]], List[str]]:
    """`--only chatter alice.zip`: the words after --only that are no milestone but an existing
    path are submissions. Returns (milestones or None, submissions)."""
    paths = [o for o in only or [] if o not in names and os.path.exists(o)]
    return [o for o in only or [] if o not in paths] or None, paths


# The exit code of a grading the TA stopped (a shell's for a command ended by SIGINT).
EXIT_INTERRUPTED = 130


def stop_on_signals(grader: Grader) -> None:
    """Ctrl+C (SIGINT) and SIGTERM stop the grading (Grader.interrupt) instead of killing it."""
    def handler(signum, _frame) -> None:
        if not grader.interrupted:
            print("%s: stopping: ending the runs under way, writing the verdicts so far"
                  % signal.Signals(signum).name, file=sys.stderr, flush=True)
        grader.interrupt()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, handler)


# Set in the environment of a grader that started itself again in the course's environment.
COURSE_ENV_MARK = "COURSE_GRADER_COURSE_ENV"


def in_course_environment() -> None:
    """Go on in the course workspace's environment alone (workspace.course_environment), marked
    as a grading of its own (course_sandbox.leftovers: what it starts is found by the mark if it is
    killed): exec this same command in it, once, unless this process already runs so."""
    if os.environ.get(COURSE_ENV_MARK) == "1" and leftovers.is_marked():
        return
    env = leftovers.marked(workspace.course_environment(workspace.course_setup()))
    env[COURSE_ENV_MARK] = "1"
    os.execve(sys.executable, [sys.executable] + sys.argv, env)


def regrade_submission(student: str, given: List[submissions.Submission], out: str
                       ) -> Tuple[List[submissions.Submission], Optional[str]]:
    """The submission to regrade `student` from: theirs among those `given`, else a copy of what the
    last grading in `out` unpacked (returned second: to remove afterwards). ValueError when `out`
    holds no earlier grading or there is nothing to regrade from."""
    if not class_outputs.earlier_students(out):
        raise ValueError("%s holds no earlier grading (no gradebook.csv and no <student>/results.json)" % out)
    mine = [s for s in given if s.name == student]
    if mine:
        return mine[:1], None
    if given:
        raise ValueError("no submission of %s among those given (%s)" % (student, ", ".join(s.name for s in given)))
    earlier = class_outputs.unpacked(out, student)
    if not os.path.isdir(earlier):
        raise ValueError("give %s's submission (a path or --class DIR): %s has none unpacked" % (student, out))
    copy = tempfile.mkdtemp(prefix="regrade-")
    shutil.copytree(earlier, os.path.join(copy, student), symlinks=True)
    return [submissions.Submission(student, os.path.join(copy, student))], copy


def similarity_lines(pairs: List) -> List[str]:
    """The terminal's word on similar pairs."""
    if not pairs:
        return []
    return ["similar: %d pair(s), e.g. %s and %s (%s, %.2f); see similarity.csv"
            % (len(pairs), pairs[0].student_a, pairs[0].student_b, pairs[0].package, pairs[0].score)]


def boilerplate_folders(course: course_file.Course, given: Sequence[str] = ()) -> List[str]:
    """What every submission may hold without copying anyone: the folders given (--boilerplate),
    the course's reference solution and the code its texts hand out (starter/), where it has them."""
    return list(given) + [f for f in (course.solution, course.starter) if f]


def has_packages(folder: str) -> bool:
    """Whether `folder` holds a catkin package (a course's solution/ that is more than a name)."""
    return bool(submissions.find_packages(folder))


def load_course(path: str) -> course_file.Course:
    """The course to grade against: `path`'s, else the built-in one."""
    return course_file.load(os.path.abspath(path) if path else course_file.builtin_course_dir())


def lms_poster(opts: argparse.Namespace, course: course_file.Course) -> Optional[lti_post.Poster]:
    """The LMS poster --lti asks for (None without it), its files checked before any grading;
    ValueError with what is wrong."""
    if not opts.lti:
        if opts.post_only or opts.dry_run or opts.lti_users:
            raise ValueError("--lti-users, --post-only and --dry-run go with --lti CONFIG")
        return None
    if not opts.lti_users:
        raise ValueError("--lti needs --lti-users FILE: each student's LMS user id (CSV student,user_id)")
    try:
        return lti_post.prepare(opts.lti, opts.lti_users, course, dry_run=opts.dry_run)
    except ConfigError as err:
        raise ValueError("the LTI configuration has errors:\n%s" % err) from err


def post_grades(poster: Optional[lti_post.Poster], out: str, code: int) -> int:
    """Post the grading in `out` with `poster`, if any: the grading's exit `code`, or
    lti_post.EXIT_PENDING when it was 0 and some score is pending."""
    if poster is None:
        return code
    summary = poster.run(out)
    print(summary.line(), flush=True)
    return code or summary.exit_code()


def main(argv: Optional[List[str]] = None) -> int:
    opts = parse(argv)
    try:
        course = load_course(opts.course)
    except course_file.CourseError as err:
        print("cannot grade: the course file has errors:\n%s" % err, file=sys.stderr)
        return 2
    try:
        poster = lms_poster(opts, course)
    except ValueError as err:
        print("cannot post to the LMS: %s" % err, file=sys.stderr)
        return 2
    if opts.post_only:
        if not class_outputs.earlier_students(os.path.abspath(opts.out)):
            print("cannot post to the LMS: %s holds no grading (no <student>/results.json)" % opts.out,
                  file=sys.stderr)
            return 2
        return post_grades(poster, os.path.abspath(opts.out), 0)
    MILESTONES: List[Milestone] = course.milestones
    if opts.list:
        for m in MILESTONES:
            check = m.test_file and os.path.basename(m.test_file) or "%d steps" % len(m.steps)
            print("%-18s %5g pts  %-24s %-20s %s" % (m.name, m.points, m.text, check, " ".join(m.packages)))
        return 0
    names = {m.name for m in MILESTONES}
    opts.only, more = split_only(opts.only, names)
    opts.submissions += more
    unknown = sorted(set(opts.only or []) - names)
    if unknown:
        print("unknown milestone(s): %s (see --list)" % ", ".join(unknown), file=sys.stderr)
        return 2
    subs = submissions.named(opts.submissions)
    if opts.class_dir:
        subs += submissions.class_submissions(opts.class_dir)
    regrade_copy = None
    if opts.regrade:
        try:
            subs, regrade_copy = regrade_submission(opts.regrade, subs, os.path.abspath(opts.out))
        except ValueError as err:
            print("cannot regrade: %s" % err, file=sys.stderr)
            return 2
    reference = not subs
    if reference and poster is not None:
        print("--lti posts students' scores: give SUBMISSION... or --class DIR (or --post-only)", file=sys.stderr)
        return 2
    if opts.results_json and len(subs) != 1:
        print("--results-json needs exactly one submission", file=sys.stderr)
        return 2
    if reference:
        solutions = course.solution if course.solution and has_packages(course.solution) else None
        if solutions is None:
            print("no submission given, and this course has no reference solutions to grade (the student "
                  "image holds none): grade SUBMISSION... or --class DIR", file=sys.stderr)
            return 2
        subs = [submissions.Submission(REFERENCE, solutions)]
    out = os.path.abspath(opts.out)
    os.makedirs(out, exist_ok=True)
    started = time.monotonic()
    ended = leftovers.sweep()
    if ended:
        print("ended what a killed grading left: %s" % ended, flush=True)
    try:
        removed = claim_output(out)
    except Busy as err:
        print("cannot grade: %s" % err, file=sys.stderr)
        return 2
    if removed:
        print("removed %s" % removed, flush=True)
    try:
        grader = Grader(MILESTONES, Options(out, opts.jobs, opts.only, opts.only_from, opts.timeout,
                                            opts.verbose or reference, [s.path for s in subs if s.path],
                                            opts.builds, opts.disk * MiB,
                                            [a for a in (course.solution, course.samples) if a],
                                            early=opts.early, typical=course_file.typical_durations(course),
                                            share_builds=opts.share_builds))
    except levels.Unavailable as err:
        release_output(out)
        print("cannot grade: %s" % err, file=sys.stderr)
        return 2
    print("isolation: %s" % grader.sandbox.describe(), flush=True)
    stop_on_signals(grader)
    class_view.plotting_loader()  # the class view's imports, done while the runs go on
    try:
        verdicts = grader.grade(subs, reference)
    finally:
        release_output(out)
        if regrade_copy:
            shutil.rmtree(regrade_copy, ignore_errors=True)
    class_verdicts = class_outputs.merged(out, opts.regrade, verdicts, MILESTONES) if opts.regrade else verdicts
    boilerplate = boilerplate_folders(course, opts.boilerplate)
    pairs = class_outputs.write(out, class_verdicts, MILESTONES, grader.sandbox.describe(), boilerplate)
    for line in class_view.summary(class_verdicts, MILESTONES) + similarity_lines(pairs):
        print(line)
    if opts.results_json:
        shutil.copyfile(os.path.join(out, subs[0].name, "results.json"), opts.results_json)
    failed = [v for v in verdicts if not v.passed]
    print("graded %d submission(s), %d milestone verdicts (%d failed) in %.1f s, --jobs %d --builds %d; see %s"
          % (len(subs), len(verdicts), len(failed), time.monotonic() - started, opts.jobs, opts.builds,
             os.path.join(out, "report.html")), flush=True)
    if grader.interrupted:
        print("interrupted: %d verdict(s) written, %d not graded" % (
            sum(v.reason != INTERRUPTED for v in verdicts), sum(v.reason == INTERRUPTED for v in verdicts)),
            flush=True)
        return post_grades(poster, out, EXIT_INTERRUPTED)
    return post_grades(poster, out, 1 if reference and failed else 0)
