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
- outputs: the last verdict until the grader exits (gradebook, report, class view);
- cpu: the CPU seconds of the grading and every process below it (a cpuacct cgroup of its own,
  when this runs as root on cgroup v1; else not shown). CPU over 2 x the wall of a phase says
  the phase waits on the cores, not on timeouts.

`--before REV` grades with the grader of another revision too (REV: a git revision, materialised
with `git worktree add` under /tmp and built there once, or the path of a checkout whose
catkin_ws and solutions_ws are built), rounds alternating before/after on the same submission,
and prints both tables and the ratios: the figures of one run, under the same load.

    python3 bench/grade_phases.py [--jobs N] [--rounds R] [--only M ...] [--before REV]
        [--before-args ARGS] [--after-args ARGS]
"""
from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Dict, List, NamedTuple, Optional, Tuple

from course_grader import workspace
from course_testkit.benchmarks import student_packages  # the same packages the class bench hands in

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
    cpu: Optional[float]  # CPU seconds of the grader and everything below it; None if not measurable


class Code(NamedTuple):
    """A grader to measure: what to call it and the setup.bash that puts it on the path."""
    label: str
    setup: Path
    args: Tuple[str, ...] = ()  # more arguments for its `grade`


CPUACCT = Path("/sys/fs/cgroup/cpuacct")
BUILD_FLAGS = ["-DPYTHON_EXECUTABLE=/usr/bin/python3", "-DCMAKE_BUILD_TYPE=Release"]


def scratch(prefix: str) -> Path:
    folder = Path(tempfile.mkdtemp(prefix=prefix))
    folder.chmod(0o755)  # the sandbox user passes through it to the student's workspace
    return folder


def submission(folder: Path) -> Path:
    """The reference's exercise packages as one student's submission."""
    sub = folder / STUDENT
    for pkg in student_packages():
        shutil.copytree(ROOT / "courses" / "robotics_labs" / "solution" / pkg, sub / pkg, symlinks=True)
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


def checkout_of(rev: str) -> Path:
    """A checkout of `rev` with both workspaces built: `rev` itself if it is such a folder, else
    a git worktree of it under /tmp (made and built on first use, reused after)."""
    given = Path(rev)
    if (given / "solutions_ws" / "devel" / "setup.bash").is_file():
        tree = given
    else:
        tree = worktree_of(rev)
    venv = ROOT / ".venv"  # the Python packages git does not hold (mujoco for the simulator)
    if venv.is_dir() and not (tree / ".venv").exists():
        (tree / ".venv").symlink_to(venv)
    return tree


def worktree_of(rev: str) -> Path:
    """A git worktree of `rev` under /tmp, its workspaces built (made on first use, reused after)."""
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", rev], check=True,
                            stdout=subprocess.PIPE, text=True).stdout.strip()
    tree = Path(tempfile.gettempdir()) / ("grade-phases-%s" % commit)
    if not tree.is_dir():
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree), commit], check=True)
    if not (tree / "solutions_ws" / "devel" / "setup.bash").is_file():
        print("building %s in %s ..." % (commit, tree), flush=True)
        flags = " ".join(BUILD_FLAGS)
        subprocess.run(["bash", "-c", "cd catkin_ws && catkin_make %s && source devel/setup.bash && "
                        "cd ../solutions_ws && catkin_make %s" % (flags, flags)], cwd=tree, check=True,
                       stdout=subprocess.DEVNULL, env=unsourced_env())
    return tree


def unsourced_env() -> Dict[str, str]:
    """This environment without this checkout's workspaces in its folder lists: a worktree built
    with them would chain them (the reference overlay included) under its own, and its grader would
    take the reference's modules for the course's (every verdict: "installs Python modules the
    course provides", in 0.0 s)."""
    return workspace.without_folders(dict(os.environ), [str(ROOT)])


def cpu_cgroup(name: str) -> Optional[Path]:
    """A fresh cpuacct cgroup (cgroup v1, root) to put one grading in; None where there is none."""
    try:
        group = CPUACCT / name
        group.mkdir(exist_ok=True)
        return group if (group / "cpuacct.usage").is_file() else None
    except OSError:
        return None


def grade_once(code: Code, sub: Path, out: Path, jobs: int, only: List[str]) -> Grading:
    started_wall = time.time()
    started = time.monotonic()
    args = ["rosrun", "course_grader", "grade", str(sub), "--out", str(out), "--jobs", str(jobs), "-v"]
    args += [a for m in only for a in ("--only", m)] + list(code.args)
    group = cpu_cgroup("grade-phases-%d" % os.getpid())
    cpu_before = int((group / "cpuacct.usage").read_text()) if group else 0
    # The shell joins the cgroup before it becomes the grader: every process below it is counted.
    join = "echo $$ > %s; " % shlex.quote(str(group / "cgroup.procs")) if group else ""
    command = "%ssource %s && exec %s" % (join, shlex.quote(str(code.setup)), " ".join(map(shlex.quote, args)))
    proc = subprocess.Popen(["bash", "-c", command], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    last_verdict = started
    found: Dict[str, tuple] = {}
    for line in proc.stdout:
        seen = VERDICT_LINE.match(line)
        if seen:
            last_verdict = time.monotonic()
            found[seen.group(1)] = (seen.group(2) == "pass", float(seen.group(3)))
    proc.wait()
    wall = time.monotonic() - started
    cpu = (int((group / "cpuacct.usage").read_text()) - cpu_before) / 1e9 if group else None
    work = out / "_work" / STUDENT
    unpacked = mtime(work / "ws" / "src") or started_wall
    built = mtime(work / "build.log") or unpacked
    runs = []
    for name, (passed, seconds) in found.items():
        run_dir = work / "runs" / name
        began = (mtime(run_dir / "sandbox_policy.json") or built) - started_wall
        runs.append(Run(name, passed, seconds, check_seconds(run_dir), began))
    return Grading(wall, unpacked - started_wall, built - unpacked, sorted(runs, key=lambda r: r.started),
                   time.monotonic() - last_verdict if found else 0.0, cpu)


def med(values: List[float]) -> float:
    return statistics.median(values) if values else 0.0


def phases(gradings: List[Grading]) -> List[Tuple[str, float]]:
    """The medians of each phase (and of the CPU seconds, when measured) over `gradings`."""
    first = [min((r.started for r in g.runs), default=0.0) for g in gradings]
    last_end = [max((r.started + r.wall for r in g.runs), default=0.0) for g in gradings]
    rows = [("wall", med([g.wall for g in gradings])),
            ("start (grader up, files unpacked)", med([g.start for g in gradings])),
            ("build (overlay in the sandbox)", med([g.build for g in gradings])),
            ("runs (first start to last end)", med([b - a for a, b in zip(first, last_end)])),
            ("outputs (last verdict to exit)", med([g.outputs for g in gradings]))]
    cpus = [g.cpu for g in gradings if g.cpu is not None]
    if cpus:
        rows.append(("cpu (grading and all below it)", med(cpus)))
    return rows


def milestones(gradings: List[Grading]) -> Dict[str, Tuple[float, float, int, int]]:
    """Per milestone: median run s, median check s, runs passed, runs; longest first."""
    names = sorted({r.milestone for g in gradings for r in g.runs},
                   key=lambda n: -med([r.wall for g in gradings for r in g.runs if r.milestone == n]))
    table = {}
    for name in names:
        mine = [r for g in gradings for r in g.runs if r.milestone == name]
        table[name] = (med([r.wall for r in mine]), med([r.check for r in mine]), sum(r.passed for r in mine), len(mine))
    return table


def report(label: str, gradings: List[Grading], jobs: int) -> None:
    print("\n%s: one submission (the reference's %d packages), --jobs %d, %d round(s), medians, load %s:"
          % (label, len(list((ROOT / "courses" / "robotics_labs" / "solution").glob("*/package.xml"))), jobs, len(gradings), load()))
    for name, value in phases(gradings):
        print("  %-34s %7.1f s" % (name, value))
    print("\n  %-16s %7s %7s %9s %s" % ("milestone", "run s", "check s", "other s", "verdicts"))
    for name, (wall, check, passed, count) in milestones(gradings).items():
        print("  %-16s %7.1f %7.1f %9.1f %d/%d passed" % (name, wall, check, wall - check, passed, count))
    runs = [r for g in gradings for r in g.runs]
    total, checks = sum(r.wall for r in runs) / len(gradings), sum(r.check for r in runs) / len(gradings)
    print("  %-16s %7.1f %7.1f %9.1f (sums per grading: the runs overlap %d at a time)"
          % ("all", total, checks, total - checks, jobs))


def compare(before: List[Grading], after: List[Grading]) -> None:
    """Both gradings' medians side by side, with after/before."""
    def ratio(a: float, b: float) -> str:
        return "%.2f" % (a / b) if b else "-"
    print("\nside by side (medians; after/before), load %s:" % load())
    print("  %-34s %8s %8s %6s" % ("phase", "before", "after", "ratio"))
    for (name, b), (_, a) in zip(phases(before), phases(after)):
        print("  %-34s %7.1fs %7.1fs %6s" % (name, b, a, ratio(a, b)))
    old, new = milestones(before), milestones(after)
    print("\n  %-16s %15s %15s %6s" % ("milestone", "before run/check", "after run/check", "ratio"))
    for name in new:
        b = old.get(name, (0.0, 0.0, 0, 0))
        a = new[name]
        print("  %-16s %7.1f/%-7.1f %7.1f/%-7.1f %6s  verdicts %d/%d -> %d/%d"
              % (name, b[0], b[1], a[0], a[1], ratio(a[0], b[0]), b[2], b[3], a[2], a[3]))


def load() -> str:
    return " ".join(Path("/proc/loadavg").read_text().split()[:3])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--jobs", type=int, default=6, help="milestone runs at once (the grader's default on 2 cores)")
    parser.add_argument("--rounds", type=int, default=1, help="gradings per grader")
    parser.add_argument("--only", action="append", default=[], metavar="M")
    parser.add_argument("--before", metavar="REV", help="also grade with the grader of REV (a git revision or a "
                        "built checkout), alternating rounds, and compare")
    parser.add_argument("--before-args", default="", help="more arguments for the before grader (e.g. "
                        "'--early 0' with --before . to compare one option of this checkout)")
    parser.add_argument("--after-args", default="", help="more arguments for this checkout's grader")
    opts = parser.parse_args()
    codes = [Code("after" if opts.before else "this checkout", ROOT / "solutions_ws" / "devel" / "setup.bash",
                  tuple(shlex.split(opts.after_args)))]
    if opts.before:
        codes.insert(0, Code("before (%s%s)" % (opts.before, " " + opts.before_args if opts.before_args else ""),
                             checkout_of(opts.before) / "solutions_ws" / "devel" / "setup.bash",
                             tuple(shlex.split(opts.before_args))))
    folder = scratch("grade-phases-")
    try:
        sub = submission(folder)
        gradings: Dict[str, List[Grading]] = {c.label: [] for c in codes}
        for i in range(opts.rounds):
            # alternate which grader goes first, so neither always meets the other's after-load
            for code in (codes if i % 2 == 0 else codes[::-1]):
                out = folder / ("grades-%d-%d" % (i, codes.index(code)))
                done = grade_once(code, sub, out, opts.jobs, opts.only)
                gradings[code.label].append(done)
                print("round %d, %s: %.1f s (load %s)" % (i + 1, code.label, done.wall, load()), flush=True)
                failed = [r.milestone for r in done.runs if not r.passed]
                if failed and len(failed) == len(done.runs) and all(r.wall == 0.0 for r in done.runs):
                    sys.exit("%s failed every milestone without running one: a broken set-up, not a figure "
                             "(grade with %s sourced to see the reason)" % (code.label, code.setup))
                if failed:
                    print("  the reference failed: %s (the figures count these runs as they went)"
                          % ", ".join(failed), flush=True)
                shutil.rmtree(out, ignore_errors=True)
        for code in codes:
            report(code.label, gradings[code.label], opts.jobs)
        if opts.before:
            compare(gradings[codes[0].label], gradings[codes[1].label])
    finally:
        shutil.rmtree(folder, ignore_errors=True)
        group = cpu_cgroup("grade-phases-%d" % os.getpid())
        if group:
            group.rmdir()  # empty by now: every grading has exited
    return 0


if __name__ == "__main__":
    sys.exit(main())
