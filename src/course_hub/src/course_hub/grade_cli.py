"""`make hub-grade` (rosrun course_hub hub_grade): at a deadline, grade the class from the hub.

    rosrun course_hub hub_grade --data /var/lib/ros-course-hub --class-list classlist.csv [--only M ...] [--jobs N]
                                [--lti CONFIG [--lti-users FILE] [--dry-run]]

1. snapshot: every student's catkin_ws/src (the hub's users/<user>/src) copied read-only into
   <data>/snapshots/<stamp>/<user>, the moment the command runs;
2. the course's grader grades that folder as a class (`rosrun course_grader grade --class ...
   --out <data>/grades/<stamp>`): the gradebook's rows are the hub's user names;
3. each student's own results (results.json, the milestones' logs, report.txt) are copied into
   their ~/grades/<stamp>/ (read-only in their workbench); the class's gradebook.csv and
   report.html stay with the TAs.

A student whose folder cannot be copied (it changed under the copy, or holds more than a
snapshot's bounds, course_hub.grading) is not graded: the others are, the gradebook gives that
student a row of empty cells, `not-graded.csv` beside it and the summary printed here say why,
and the student's ~/grades/<stamp>/report.txt says so too.

With --lti CONFIG (lti.yaml, course_lti.config), each graded student's scores then go to the LMS
gradebook (LTI 1.3 AGS, course_lti.post), the student known by the identity the hub's LTI login
recorded in <data>/lti-users.json (--lti-users); a student not graded gets no score, so no earlier
grade is overwritten with 0. What could not be posted is listed in the grading's
lti-pending.json; `rosrun course_grader grade --lti CONFIG --lti-users <data>/lti-users.json
--post-only --out <data>/grades/<stamp>` posts it later. Both files are checked before the snapshot.

Every snapshot and every grading's output is root's alone once the grading is done: a later
grading's student code (the sandbox's user) cannot read them (course_hub.layout.data_modes).

Exit code: the grader's (0 when it graded everyone), 1 when some student was not graded, 2 on a
bad class list, data folder or LTI configuration, 3 when everyone was graded but some score could
not be posted to the LMS.
"""
from __future__ import annotations

import argparse
import csv
import datetime
import os
import subprocess
import sys
from typing import Dict, List, Optional, Sequence

from course_format import course_file
from course_lti import post as lti_post
from course_lti.config import ConfigError

from course_hub import classlist, grading, layout

NOT_GRADED = "not-graded.csv"
LTI_USERS = "lti-users.json"  # in the data folder: hub user -> LMS identity, written by the LTI login


def parse(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="hub_grade", description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", required=True, help="the hub's data folder (CourseSpawner.data_dir)")
    parser.add_argument("--class-list", required=True, help="the class list CSV: its students are graded")
    parser.add_argument("--out", default="", help="the grader's output (default <data>/grades/<stamp>)")
    parser.add_argument("--only", action="extend", nargs="+", default=[], metavar="M", help="only these milestones")
    parser.add_argument("--jobs", type=int, default=0, help="the grader's parallel runs (default: its own)")
    parser.add_argument("--stamp", default="", help="the snapshot's name (default: UTC time, 20261126T160000Z)")
    parser.add_argument("--lti", metavar="CONFIG", default="",
                        help="then post the scores to the LMS gradebook (LTI 1.3 AGS) as CONFIG (lti.yaml) says")
    parser.add_argument("--lti-users", metavar="FILE", default="",
                        help="with --lti: each user's LMS identity (default <data>/%s)" % LTI_USERS)
    parser.add_argument("--dry-run", action="store_true",
                        help="with --lti: print the requests that would go to the LMS, send nothing")
    return parser.parse_args(list(argv))


def grade_command(class_dir: str, out: str, only: List[str], jobs: int) -> List[str]:
    command = ["rosrun", "course_grader", "grade", "--class", class_dir, "--out", out]
    if only:
        command += ["--only"] + list(only)
    if jobs:
        command += ["--jobs", str(jobs)]
    return command


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = parse(sys.argv[1:] if argv is None else argv)
    try:
        students = classlist.load(args.class_list).students
    except classlist.ClassListError as err:
        print("hub_grade: %s" % err, file=sys.stderr)
        return 2
    if not os.path.isdir(os.path.join(args.data, "users")):
        print("hub_grade: %s holds no users/ folder: is it the hub's data folder?" % args.data, file=sys.stderr)
        return 2
    try:
        poster = lms_poster(args)
    except (ConfigError, course_file.CourseError) as err:
        print("hub_grade: cannot post to the LMS:\n%s" % err, file=sys.stderr)
        return 2
    stamp = args.stamp or datetime.datetime.now(datetime.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    layout.lay_out(args.data)
    class_dir = os.path.join(args.data, "snapshots", stamp)
    out = args.out or os.path.join(args.data, "grades", stamp)
    if os.path.exists(class_dir):
        print("hub_grade: the snapshot %s exists already: pick another --stamp" % class_dir, file=sys.stderr)
        return 2
    counts = grading.snapshot(args.data, class_dir, students)
    not_graded = {user: count.error for user, count in counts.items() if count.error}
    for user, count in counts.items():
        if count.error:
            print("hub_grade: NOT GRADED %s: %s" % (user, count.error), flush=True)
            continue
        skipped = " (%d special files left out)" % len(count.skipped) if count.skipped else ""
        print("hub_grade: snapshot %s: %d files%s" % (user, count.files, skipped), flush=True)
    print("hub_grade: snapshot of %d students, read-only, in %s" % (len(counts) - len(not_graded), class_dir),
          flush=True)
    os.makedirs(out, mode=0o711, exist_ok=True)
    done = subprocess.run(grade_command(class_dir, out, args.only, args.jobs), check=False)
    record_not_graded(out, not_graded)
    written, failed = grading.publish(out, args.data, students, stamp, not_graded)
    os.chmod(out, 0o700)  # done: no later grading's student code reads it
    for user, why in failed.items():
        print("hub_grade: %s's report not written: %s" % (user, why), flush=True)
    print("hub_grade: reports copied to %d students' ~/grades/%s; the gradebook: %s" % (
        len(written), stamp, os.path.join(out, "gradebook.csv")), flush=True)
    if not_graded:
        print("hub_grade: %d student(s) NOT GRADED (%s): see %s" % (
            len(not_graded), ", ".join(sorted(not_graded)), os.path.join(out, NOT_GRADED)), flush=True)
    lms = 0
    if poster is not None:
        summary = poster.run(out)
        print("hub_grade: %s" % summary.line(), flush=True)
        lms = summary.exit_code()
    return done.returncode or (1 if not_graded else 0) or lms


def lms_poster(args: argparse.Namespace) -> Optional[lti_post.Poster]:
    """The LMS poster --lti asks for (None without it), checked before the snapshot: ConfigError or
    CourseError. The hub grades the built-in course; its users file may not exist yet (nobody
    opened the course from the LMS): every score is then pending."""
    if not args.lti:
        if args.lti_users or args.dry_run:
            raise ConfigError(["--lti-users and --dry-run go with --lti CONFIG"])
        return None
    course = course_file.load(course_file.builtin_course_dir())
    users = args.lti_users or os.path.join(args.data, LTI_USERS)
    return lti_post.prepare(args.lti, users, course, dry_run=args.dry_run, missing_users_ok=not args.lti_users,
                            say=lambda line: print("hub_grade: %s" % line, flush=True))


def record_not_graded(out: str, not_graded: Dict[str, str]) -> None:
    """`not-graded.csv` (user, reason) and a row of empty cells per such user in the gradebook."""
    if not not_graded:
        return
    with open(os.path.join(out, NOT_GRADED), "w", newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(["student", "reason"])
        writer.writerows(sorted(not_graded.items()))
    gradebook = os.path.join(out, "gradebook.csv")
    header: List[str] = ["student", "total", "max"]
    if os.path.exists(gradebook):
        with open(gradebook, newline="") as stream:
            header = next(csv.reader(stream), header)
    with open(gradebook, "a", newline="") as stream:
        writer = csv.writer(stream)
        if not os.path.getsize(gradebook):
            writer.writerow(header)
        writer.writerows([user] + [""] * (len(header) - 1) for user in sorted(not_graded))
