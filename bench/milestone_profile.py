#!/usr/bin/env python3
"""Where a milestone run spends its time and CPU: the grader run on the reference (or on the
submissions given), one milestone at a time (`--jobs 1`), while every process under it is
sampled from /proc every 20 ms.

For each milestone: its wall time, the CPU seconds of each kind of process (rostest with its
in-process master, roslaunch's rosout, turtlesim, the check, the student's nodes, the sandbox,
the build), and when each kind started and ended, relative to the run's start. The last table
adds the kinds up over all milestones: what a whole grading costs, by kind.

    python3 bench/milestone_profile.py                      # every milestone of the reference
    python3 bench/milestone_profile.py --only chatter arch  # some
    python3 bench/milestone_profile.py courses/robotics_labs/samples/lab2_chatter_scripts --only chatter
"""
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from collections import defaultdict
from pathlib import Path
from typing import Dict, List, Tuple

from course_checks.rostest_runner import ROSTEST_MAIN
from course_sandbox import procs

SAMPLE_S = 0.02


def kind_of(cmdline: List[str]) -> str:
    """What a process is in a milestone run, from its command line."""
    words = " ".join(cmdline)
    name = os.path.basename(cmdline[0]) if cmdline else ""
    script = next((os.path.basename(w) for w in cmdline[1:3] if w.startswith("/") or w.endswith(".py")), "")
    if name in ("bwrap", "nsenter", "unshare") or "course_sandbox" in words:
        return "sandbox (%s)" % (name if name in ("bwrap", "nsenter", "unshare") else "course_sandbox")
    if "catkin_make" in words or name in ("cmake", "make", "gmake", "cc1plus", "c++", "g++", "ld", "collect2",
                                          "as", "cc1", "gcc"):
        return "build"
    if script == "rostest" or name == "rostest" or ROSTEST_MAIN in cmdline:
        return "rostest + master"
    if script == "rosout" or name == "rosout":
        return "rosout"
    if script == "turtlesim_node" or name == "turtlesim_node":
        return "turtlesim"
    if script.endswith("_check") or script.endswith("_check.py"):
        return "check"
    if "mujoco" in words or "gzserver" in words or "gazebo" in script:
        return "simulator (MuJoCo)"
    if script == "grade" or "course_grader" in words:
        return "grader"
    if name in ("python3", "python3.11") and script:
        return "other python: %s" % script
    return "other: %s" % (script or name)


def snapshot(root: int) -> Dict[int, Tuple[str, float]]:
    """Every process under `root`: pid -> (kind, CPU seconds so far); kind "" once it has exited."""
    found = {}
    for pid in procs.descendants(root):
        use = procs.usage(pid)
        try:
            with open("/proc/%d/cmdline" % pid, "rb") as f:
                cmdline = [w.decode(errors="replace") for w in f.read().split(b"\0") if w]
        except OSError:
            continue
        if use is not None:
            found[pid] = (kind_of(cmdline) if cmdline else "", use.cpu_seconds)
    return found


class Sampler(threading.Thread):
    """Samples the process tree under a pid until stopped: per pid its kind, first and last
    time seen, and its CPU seconds at the last sample."""

    def __init__(self, root: int) -> None:
        super().__init__(daemon=True)
        self.root = root
        self.seen: Dict[int, list] = {}
        self.halt = threading.Event()
        self.started = time.monotonic()

    def run(self) -> None:
        while not self.halt.is_set():
            now = time.monotonic() - self.started
            for pid, (kind, cpu) in snapshot(self.root).items():
                row = self.seen.setdefault(pid, [kind, now, now, cpu])
                row[0] = kind or row[0]  # the kind it has last (after an exec, what it became)
                row[2], row[3] = now, cpu
            self.halt.wait(SAMPLE_S)


def profile(milestone: str, submissions: List[str], scratch: Path) -> Tuple[float, Dict[str, list]]:
    """Grade one milestone; (wall s, {kind: [cpu s, first start, last end, processes]})."""
    out = scratch / milestone
    command = ["rosrun", "course_grader", "grade", "--jobs", "1", "--only", milestone, "--out", str(out)]
    started = time.monotonic()
    proc = subprocess.Popen(command + submissions, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    sampler = Sampler(proc.pid)
    sampler.started = started
    sampler.start()
    proc.wait()
    sampler.halt.set()
    sampler.join()
    wall = time.monotonic() - started
    kinds: Dict[str, list] = {}
    for kind, first, last, cpu in sampler.seen.values():
        row = kinds.setdefault(kind, [0.0, first, last, 0])
        row[0] += cpu
        row[1], row[2], row[3] = min(row[1], first), max(row[2], last), row[3] + 1
    return wall, kinds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("submissions", nargs="*", help="submissions (default: the reference)")
    parser.add_argument("--only", nargs="+", help="milestones (default: all)")
    opts = parser.parse_args()
    from course_format import course_file
    MILESTONES = course_file.load(course_file.builtin_course_dir()).milestones
    names = opts.only or [m.name for m in MILESTONES]
    scratch = Path(tempfile.mkdtemp(prefix="milestone-profile-"))
    scratch.chmod(0o755)
    totals: Dict[str, float] = defaultdict(float)
    walls = 0.0
    print("milestone runs one at a time (--jobs 1), processes sampled every %.0f ms; load average %.1f on %d cores"
          % (SAMPLE_S * 1000, os.getloadavg()[0], os.cpu_count()))
    try:
        for name in names:
            wall, kinds = profile(name, [os.path.abspath(s) for s in opts.submissions], scratch)
            walls += wall
            cpu = sum(row[0] for row in kinds.values())
            print("\n%s: %.1f s wall, %.1f CPU s" % (name, wall, cpu))
            print("  %-30s %7s %8s %8s %6s" % ("kind", "CPU s", "from s", "to s", "procs"))
            for kind, (seconds, first, last, count) in sorted(kinds.items(), key=lambda kv: -kv[1][0]):
                totals[kind] += seconds
                print("  %-30s %7.2f %8.2f %8.2f %6d" % (kind, seconds, first, last, count))
            sys.stdout.flush()
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    print("\nall %d milestones: %.1f s wall one after the other, %.1f CPU s" % (len(names), walls, sum(totals.values())))
    for kind, seconds in sorted(totals.items(), key=lambda kv: -kv[1]):
        print("  %-30s %7.2f CPU s  %5.1f%%" % (kind, seconds, 100 * seconds / max(sum(totals.values()), 1e-9)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
