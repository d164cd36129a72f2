#!/usr/bin/env python3
"""Where one submission's grading time goes (issue 23, item 4), as figures, never assertions.

The reference's exercise packages are graded as a student's submission (copied, built in the
sandbox as an overlay, each milestone run as a rostest with the student's processes sandboxed):
`rosrun course_grader grade SUB --out OUT -v`. The phases are read back from what the grading
leaves, so the grader is measured as it is:

- start: the grader's own start-up until the submission is unpacked and its packages laid out in
  the workspace (the workspace's src folder: catkin_make's first act is a link in it);
- build: from there until the overlay is built (its build.log written);
- runs: the milestones' rostests, at most --jobs at once; for each, its wall time, the time its
  check's test cases took (the check's JUnit), and the rest: rostest's master and launch, the
  world (turtlesim, the simulator) starting, the check's own start-up, the ends;
- outputs: the last verdict until the grader exits (gradebook, report, class view).

    python3 bench/grade_phases.py [--jobs N] [--rounds R] [--only M ...]
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Dict, List, NamedTuple, Optional

ROOT = Path(__file__).resolve().parents[1]
STUDENT = "student"
VERDICT_LINE = re.compile(r"^\s+%s\s+(\S+)\s+(pass|FAIL)\s+([\d.]+)s" % STUDENT)


class Run(NamedTuple):
    milestone: str
    passed: bool
    wall: float  # the rostest run, as the grader timed it
    check: float  # the check's test cases (its JUnit's times)
    started: float  # seconds after the grader started


class Grading(NamedTuple):
    wall: float
    start: float
    build: float
    runs: List[Run]
    outputs: float


def scratch(prefix: str) -> Path:
    folder = Path(tempfile.mkdtemp(prefix=prefix))
    folder.chmod(0o755)  # the sandbox user passes through it to the student's workspace
    return folder


def submission(folder: Path) -> Path:
    """The reference's exercise packages as one student's submission."""
    sys.path.insert(0, str(ROOT / "bench"))
    from grade_bench import student_packages  # the same packages the class bench hands in
    sub = folder / STUDENT
    for pkg in student_packages():
        shutil.copytree(ROOT / "solutions" / pkg, sub / pkg, symlinks=True)
    return sub


def check_seconds(run_dir: Path) -> float:
    """The check's test cases' time, from the rosunit JUnit of the run (0 when none)."""
    total = 0.0
    for path in run_dir.glob("ros_home/test_results/*/rosunit-*.xml"):
        try:
            total += sum(float(case.get("time", "0") or 0) for case in ET.parse(path).iter("testcase"))
        except (ET.ParseError, OSError, ValueError):
            pass
    return total


def mtime(path: Path) -> Optional[float]:
    try:
        return path.stat().st_mtime
    except OSError:
        return None


def grade_once(sub: Path, out: Path, jobs: int, only: List[str]) -> Grading:
    started_wall = time.time()
    started = time.monotonic()
    args = ["rosrun", "course_grader", "grade", str(sub), "--out", str(out), "--jobs", str(jobs), "-v"]
    args += [a for m in only for a in ("--only", m)]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    last_verdict = started
    found: Dict[str, tuple] = {}
    for line in proc.stdout:
        seen = VERDICT_LINE.match(line)
        if seen:
            last_verdict = time.monotonic()
            found[seen.group(1)] = (seen.group(2) == "pass", float(seen.group(3)))
    proc.wait()
    wall = time.monotonic() - started
    work = out / "_work" / STUDENT
    unpacked = mtime(work / "ws" / "src") or started_wall
    built = mtime(work / "build.log") or unpacked
    runs = []
    for name, (passed, seconds) in found.items():
        run_dir = work / "runs" / name
        began = (mtime(run_dir / "sandbox_policy.json") or built) - started_wall
        runs.append(Run(name, passed, seconds, check_seconds(run_dir), began))
    return Grading(wall, unpacked - started_wall, built - unpacked, sorted(runs, key=lambda r: r.started),
                   time.monotonic() - last_verdict if found else 0.0)


def report(gradings: List[Grading], jobs: int) -> None:
    def med(values: List[float]) -> float:
        return statistics.median(values) if values else 0.0
    print("\none submission (the reference's %d packages), --jobs %d, %d round(s), medians:"
          % (len(list((ROOT / "solutions").glob("*/package.xml"))), jobs, len(gradings)))
    print("  %-34s %7.1f s" % ("wall", med([g.wall for g in gradings])))
    print("  %-34s %7.1f s" % ("start (grader up, files unpacked)", med([g.start for g in gradings])))
    print("  %-34s %7.1f s" % ("build (overlay in the sandbox)", med([g.build for g in gradings])))
    first = [min((r.started for r in g.runs), default=0.0) for g in gradings]
    last_end = [max((r.started + r.wall for r in g.runs), default=0.0) for g in gradings]
    print("  %-34s %7.1f s" % ("runs (first start to last end)", med([b - a for a, b in zip(first, last_end)])))
    print("  %-34s %7.1f s" % ("outputs (last verdict to exit)", med([g.outputs for g in gradings])))
    names = sorted({r.milestone for g in gradings for r in g.runs},
                   key=lambda n: -med([r.wall for g in gradings for r in g.runs if r.milestone == n]))
    print("\n  %-16s %7s %7s %9s %s" % ("milestone", "run s", "check s", "other s", "verdicts"))
    for name in names:
        mine = [r for g in gradings for r in g.runs if r.milestone == name]
        wall, check = med([r.wall for r in mine]), med([r.check for r in mine])
        print("  %-16s %7.1f %7.1f %9.1f %d/%d passed" % (name, wall, check, wall - check,
                                                        sum(r.passed for r in mine), len(mine)))
    runs = [r for g in gradings for r in g.runs]
    total, checks = sum(r.wall for r in runs) / len(gradings), sum(r.check for r in runs) / len(gradings)
    print("  %-16s %7.1f %7.1f %9.1f (sums per grading: the runs overlap %d at a time)"
          % ("all", total, checks, total - checks, jobs))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--jobs", type=int, default=6, help="milestone runs at once (the grader's default on 2 cores)")
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--only", action="append", default=[], metavar="M")
    opts = parser.parse_args()
    folder = scratch("grade-phases-")
    try:
        sub = submission(folder)
        gradings = []
        for i in range(opts.rounds):
            out = folder / ("grades-%d" % i)
            gradings.append(grade_once(sub, out, opts.jobs, opts.only))
            print("round %d: %.1f s" % (i + 1, gradings[-1].wall), flush=True)
        report(gradings, opts.jobs)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
