#!/usr/bin/env python3
"""Trust and speed of the grader (issue "Grade a class", item 8), as figures, never as assertions.

- Trust: the reference solutions graded RUNS times in a row (`rosrun course_grader grade`, every
  milestone). Every milestone must pass on the reference, so any failure is a wrong verdict; the
  bench counts them per milestone and prints their reasons.
- Speed: the wall time of each reference grading (one submission's full milestone set; target
  <= 30 s on 2 cores, median), and a class of N copies of the reference's exercise packages graded
  as student submissions (target: 30 in <= 12 min), with the grader's progress line per submission.
  Where a run's time and CPU go: bench/milestone_profile.py.
- turtlesim start-up (launch to /spawn; target <= 0.45 s): see bench/turtlesim_bench.py --startup.

    python3 bench/grade_bench.py [--runs 20] [--class-size 30] [--jobs N]
    python3 bench/grade_bench.py --runs 0 --class-size 5     # only a small class
    python3 bench/grade_bench.py --sandbox-cost 4 --rounds 2 # the sandbox's cost on a class
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path
from typing import Dict, List, Tuple

from course_testkit.benchmarks import student_packages

ROOT = Path(__file__).resolve().parents[1]
REFERENCE_TARGET_S = 30.0
CLASS_TARGET_S_PER_30 = 12 * 60.0


def scratch_folder(prefix: str) -> Path:
    """A temporary folder the sandbox user can pass through (mkdtemp makes it 0700)."""
    folder = Path(tempfile.mkdtemp(prefix=prefix))
    folder.chmod(0o755)
    return folder


def grade(args: List[str], out: Path, level: str = "") -> Tuple[float, str]:
    """Run the grader (with `level`, COURSE_SANDBOX_LEVEL: a weaker sandbox); its wall time and
    output (streamed to our stdout as it comes)."""
    started = time.monotonic()
    env = dict(os.environ, COURSE_SANDBOX_LEVEL=level) if level else None
    proc = subprocess.Popen(["rosrun", "course_grader", "grade", "--out", str(out)] + args,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    lines = []
    for line in proc.stdout:
        lines.append(line)
        print("    " + line.rstrip(), flush=True)
    proc.wait()
    return time.monotonic() - started, "".join(lines)


def verdicts(out: Path) -> Dict[Tuple[str, str], Dict]:
    """(student, milestone) -> the Gradescope test entry, from every results.json under `out`."""
    found = {}
    for results in out.glob("*/results.json"):
        for test in json.loads(results.read_text())["tests"]:
            found[(results.parent.name, test["name"].split(":", 1)[0])] = test
    return found


def reference_runs(runs: int, jobs: List[str]) -> None:
    times: List[float] = []
    wrong: Counter = Counter()
    reasons: Dict[str, List[str]] = {}
    graded = 0
    for i in range(runs):
        out = scratch_folder("grade-bench-")
        try:
            print("reference run %d/%d" % (i + 1, runs), flush=True)
            elapsed, _ = grade(jobs, out)
            times.append(elapsed)
            for (_, milestone), test in verdicts(out).items():
                graded += 1
                if test["status"] != "passed":
                    wrong[milestone] += 1
                    reasons.setdefault(milestone, []).append(test["output"].strip().splitlines()[0][:200]
                                                             if test["output"].strip() else "(no output)")
        finally:
            shutil.rmtree(out, ignore_errors=True)
    print("\nreference graded %d times: %d milestone verdicts, %d wrong" % (runs, graded, sum(wrong.values())))
    for milestone, count in wrong.most_common():
        print("  %-16s %d wrong: %s" % (milestone, count, " | ".join(reasons[milestone][:3])))
    if times:
        print("one submission, full milestone set: median %.1f s, min %.1f s, max %.1f s (target <= %.0f s)"
              % (statistics.median(times), min(times), max(times), REFERENCE_TARGET_S))


def make_class(scratch: Path, size: int) -> Path:
    """`size` submissions, each a copy of the reference's exercise packages."""
    classroom = scratch / "class"
    packages = student_packages()
    for n in range(1, size + 1):
        for pkg in packages:
            shutil.copytree(ROOT / "courses" / "robotics_labs" / "solution" / pkg, classroom / ("student%02d" % n) / pkg, symlinks=True)
    print("class of %d submissions (packages: %s)" % (size, " ".join(packages)), flush=True)
    return classroom


def class_run(size: int, jobs: List[str]) -> None:
    scratch = scratch_folder("grade-bench-class-")
    try:
        classroom = make_class(scratch, size)
        elapsed, _ = grade(["--class", str(classroom)] + jobs, scratch / "grades")
        results = verdicts(scratch / "grades")
        failed = sorted("%s/%s" % key for key, test in results.items() if test["status"] != "passed")
        print("\nclass of %d: %.1f s (%.1f s per submission; 30 would take %.1f min, target <= %.0f min); "
              "%d verdicts, %d wrong%s" % (size, elapsed, elapsed / size, elapsed / size * 30 / 60,
                                           CLASS_TARGET_S_PER_30 / 60, len(results), len(failed),
                                           (": " + ", ".join(failed)) if failed else ""))
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def sandbox_cost(size: int, rounds: int, jobs: List[str]) -> None:
    """The same class graded with the sandbox this machine gives and with limits alone
    (COURSE_SANDBOX_LEVEL=none: no namespaces, no user switch), alternating which goes first;
    the medians and their ratio."""
    scratch = scratch_folder("grade-bench-sandbox-")
    times: Dict[str, List[float]] = {"sandbox": [], "none": []}
    try:
        classroom = make_class(scratch, size)
        for i in range(rounds):
            order = ["none", "sandbox"] if i % 2 == 0 else ["sandbox", "none"]
            for mode in order:
                out = scratch / ("grades-%s-%d" % (mode, i))
                elapsed, _ = grade(["--class", str(classroom)] + jobs, out, "none" if mode == "none" else "")
                failed = [k for k, t in verdicts(out).items() if t["status"] != "passed"]
                times[mode].append(elapsed)
                print("round %d, %s: %.1f s, %d wrong verdicts" % (i + 1, mode, elapsed, len(failed)), flush=True)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    with_box, without = statistics.median(times["sandbox"]), statistics.median(times["none"])
    print("\nclass of %d, %d rounds: sandbox median %.1f s, limits alone median %.1f s: ratio %.3f "
          "(target <= 1.10)" % (size, rounds, with_box, without, with_box / without))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=20, help="reference gradings in a row (default 20)")
    parser.add_argument("--class-size", type=int, default=30, help="submissions in the class run (0: none)")
    parser.add_argument("--jobs", type=int, help="the grader's --jobs (default: the grader's own)")
    parser.add_argument("--sandbox-cost", type=int, metavar="N", default=0,
                        help="instead: a class of N graded with and without the sandbox, alternating")
    parser.add_argument("--rounds", type=int, default=2, help="with --sandbox-cost: gradings per mode")
    opts = parser.parse_args()
    jobs = ["--jobs", str(opts.jobs)] if opts.jobs else []
    print("machine: %d cores, load average %s" % (os.cpu_count() or 0, " ".join("%.2f" % x for x in os.getloadavg())))
    if opts.sandbox_cost:
        sandbox_cost(opts.sandbox_cost, opts.rounds, jobs)
        return 0
    if opts.runs:
        reference_runs(opts.runs, jobs)
    if opts.class_size:
        class_run(opts.class_size, jobs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
