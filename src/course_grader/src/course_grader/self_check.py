"""course-check (rosrun course_grader self_check): a student grades their own workspace before
submitting, with the course's grader, on the milestones of the packages it finds.

    course-check [SRC] [--out DIR] [--only M ...] [--jobs N]

SRC defaults to ~/catkin_ws/src, DIR to ~/course-check. It is `rosrun course_grader grade SRC
--out DIR`, the command a TA grades a class with (the same build in a sandbox, the same checks,
the same verdicts), then each milestone's verdict with its reason, and where the report is.
Exit code: 0 when every milestone graded passed, 1 when one failed, 2 when there was nothing to
grade or the grader could not start.
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
from typing import List, Optional, Sequence

from course_grader import cli, submissions

DEFAULT_SRC = os.path.join("~", "catkin_ws", "src")
DEFAULT_OUT = os.path.join("~", "course-check")


def parse(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="course-check", description=__doc__.split("\n\n")[0])
    parser.add_argument("src", nargs="?", default=DEFAULT_SRC,
                        help="the folder of your packages (default %s)" % DEFAULT_SRC)
    parser.add_argument("--out", default=DEFAULT_OUT, help="where the report goes (default %s)" % DEFAULT_OUT)
    parser.add_argument("--only", action="extend", nargs="+", metavar="M", help="grade only these milestones")
    parser.add_argument("--jobs", "-j", type=int, help="milestone runs at once (default: the grader's)")
    return parser.parse_args(list(argv))


def verdict_lines(results: dict) -> List[str]:
    """A line per milestone, `PASS name` or `FAIL name`, each failure's reason below it (the
    output's first part; the logs' tails are in the report)."""
    lines = []
    for test in results.get("tests", []):
        passed = test.get("status") == "passed"
        lines.append("%s  %s" % ("PASS" if passed else "FAIL", test.get("name", "?")))
        if not passed:
            reason = test.get("output", "").split("\n\n")[0]
            if reason.startswith("FAILED: "):
                reason = reason[len("FAILED: "):]
            lines.extend("      " + line for line in reason.splitlines())
    return lines


def main(argv: Optional[Sequence[str]] = None) -> int:
    opts = parse(sys.argv[1:] if argv is None else argv)
    src = os.path.abspath(os.path.expanduser(opts.src))
    out = os.path.abspath(os.path.expanduser(opts.out))
    if not os.path.isdir(src):
        print("course-check: %s is not a folder: give the folder your packages are in (default %s)"
              % (src, DEFAULT_SRC), file=sys.stderr)
        return 2
    packages = submissions.find_packages(src)
    if not packages:
        print("course-check: no catkin package in %s (no package.xml): create one first, e.g. "
              "cd %s && catkin_create_pkg chatter rospy std_msgs" % (src, src), file=sys.stderr)
        return 2
    if os.path.realpath(out) == os.path.realpath(src) or os.path.realpath(out).startswith(
            os.path.realpath(src) + os.sep):
        print("course-check: --out %s is inside %s: the report must go elsewhere" % (out, src), file=sys.stderr)
        return 2
    print("course-check: grading your packages in %s (%s) with the course's grader, as your TA does"
          % (src, ", ".join(sorted(p.name or os.path.basename(p.path) for p in packages))), flush=True)
    name = submissions.student_name(src)
    shutil.rmtree(os.path.join(out, name), ignore_errors=True)  # no verdict of an earlier check stays
    argv_grade = [src, "--out", out] + (["--only"] + opts.only if opts.only else []) \
        + (["--jobs", str(opts.jobs)] if opts.jobs else [])
    code = cli.main(argv_grade)
    results_path = os.path.join(out, name, "results.json")
    if code != 0 or not os.path.isfile(results_path):
        print("course-check: the grader gave no verdict (exit code %d): see above" % code, file=sys.stderr)
        return 2
    with open(results_path) as f:
        results = json.load(f)
    print("", flush=True)
    for line in verdict_lines(results):
        print(line)
    for line in results.get("output", "").splitlines():  # the count, then the isolation the sandbox gave
        print("course-check: %s" % line)
    print("course-check: the report, with each milestone's logs: %s (in JupyterLab: open it from the file "
          "browser)" % os.path.join(out, "report.html"), flush=True)
    return 0 if all(t.get("status") == "passed" for t in results.get("tests", [])) else 1
