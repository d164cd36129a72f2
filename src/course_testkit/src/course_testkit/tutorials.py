"""ROS 1's own tutorials as an overlay on the course workspace: the steps of their end-to-end suite
(tests/e2e/test_tutorials.py, `make tutorials-check TUTORIALS=DIR`; docs/noetic_cxx.md).

DIR holds three source trees, fetched by whoever runs it (they are never committed here):
ros_tutorials and common_tutorials (branch noetic-devel) and geometry_tutorials (its Noetic
branch, kinetic-devel). The suite:

1. copies them into a fresh overlay workspace, leaving out upstream's C++ turtlesim (ours must
   be the one the demos drive), and builds it the way the grader builds a student's packages:
   `source <course>/catkin_ws/devel/setup.bash && catkin_make` (with -k, so that every package
   that fails is named, with the reason the caller's `explain` gives: course_grader's one line);
2. runs what they have of tests, `catkin_make run_tests`, and reads catkin_test_results'
   summary (rostest exits 0 even when a test fails, so its exit code says nothing);
3. runs turtle_tf2's demo, Python (turtle_tf2_demo.launch) and C++ (turtle_tf2_demo_cpp.launch),
   against our turtlesim on a private master: once turtle2 has caught up from where the listener
   spawned it, turtle1 drives an arc, stops, and /turtle2/pose must come back to /turtle1/pose
   (the probe, a node of the demo's master, is the caller's: tests/e2e/tutorials_probe.py).

Everything it starts carries one run token and is gone when it ends.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import time
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Callable, Dict, List, NamedTuple, Sequence

CHECKOUT = Path(__file__).resolve().parents[4]  # <checkout>/src/course_testkit/src/course_testkit/tutorials.py
TREES = ("ros_tutorials", "geometry_tutorials", "common_tutorials")
LEFT_OUT = {"ros_tutorials/turtlesim": "upstream's C++ turtlesim: the demos must drive ours"}
BUILD_TIMEOUT_S = 1800.0
TESTS_TIMEOUT_S = 1200.0
START_TIMEOUT_S = 90.0  # roslaunch, turtlesim and turtle2's spawn on a loaded 2-core machine
DEMOS = (("Python", "turtle_tf2_demo.launch"), ("C++", "turtle_tf2_demo_cpp.launch"))
# The probe: turtle1 drives an arc (2 m/s, 1 rad/s) for DRIVE_S, then turtle2 has FOLLOW_S.
CAUGHT_UP_M = 0.5
DRIVE_S = 3.0
FOLLOW_S = 12.0
SAMPLE_S = 0.5
FOLLOWED_M = 0.5  # where turtle2 must be at the end, from turtle1
MOVED_AWAY_M = 1.5  # how far the drive must have taken turtle1 from turtle2


def run_logged(command: Sequence[str], env: Dict[str, str], cwd: Path, log: Path, timeout: float) -> int:
    """Run `command` with its output in `log`; its exit code. PWD is set: catkin_make takes its
    workspace from it."""
    with open(log, "wb") as out:
        return subprocess.run(list(command), env=dict(env, PWD=str(cwd)), cwd=str(cwd), stdout=out,
                              stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, timeout=timeout).returncode


# --- 1. build ---------------------------------------------------------------------------------

class Build(NamedTuple):
    ok: bool
    packages: List[str]  # in catkin's topological order
    failed: List[str]  # the packages (folders below src/) with a target that did not build
    reason: str
    seconds: float


def copy_sources(tutorials: Path, src: Path) -> List[str]:
    """The three trees into `src`, less LEFT_OUT; what was left out, with why."""
    src.mkdir(parents=True)
    for tree in TREES:
        shutil.copytree(tutorials / tree, src / tree, symlinks=True,
                        ignore=lambda folder, names: [n for n in names if n == ".git"
                                                      or "%s/%s" % (Path(folder).name, n) in LEFT_OUT])
    return ["%s (%s)" % item for item in LEFT_OUT.items()]


def build(ws: Path, course_setup: Path, explain: Callable[[str, str], str]) -> Build:
    """catkin_make -k of the overlay `ws` on the course's `course_setup`; a failed build's reason is
    `explain(build log, ws)`."""
    start = time.monotonic()
    command = ("source %s && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -k"
               % subprocess.list2cmdline([str(course_setup)]))
    fresh = {k: v for k, v in os.environ.items() if k != "CPLUS_INCLUDE_PATH"}  # only the hook sets it
    code = run_logged(["bash", "-c", command], fresh, ws, ws / "build.log", BUILD_TIMEOUT_S)
    log = (ws / "build.log").read_text(errors="replace")
    packages = re.findall(r"^-- ~~  - (\S+)", log, re.MULTILINE)
    failed = sorted(set(re.findall(r"^make\[\d+\]: \*\*\* \[(\S+?)/CMakeFiles/", log, re.MULTILINE)))
    reason = ""
    if code != 0:
        reason = explain(log, str(ws))
    return Build(code == 0, packages, failed, reason, time.monotonic() - start)


# --- 2. tests ---------------------------------------------------------------------------------

class Tests(NamedTuple):
    ok: bool
    summary: str  # catkin_test_results' own line
    counts: Dict[str, int]
    files: int
    failing: List[str]
    seconds: float


def junit_failures(results: Path) -> List[str]:
    """Each test case that failed or erred, as `file: case`."""
    failing = []
    for path in sorted(results.rglob("*.xml")):
        try:
            root = ET.parse(str(path)).getroot()
        except ET.ParseError:
            failing.append("%s: not valid XML" % path.name)
            continue
        for case in root.iter("testcase"):
            if case.find("failure") is not None or case.find("error") is not None:
                failing.append("%s: %s" % (path.name, case.get("name")))
    return failing


def run_tests(ws: Path, env: Dict[str, str]) -> Tests:
    from course_checks import isolation
    start = time.monotonic()
    token = isolation.new_token()
    try:  # one rostest at a time: the tutorials' tests time their talkers and listeners
        run_logged(["catkin_make", "run_tests", "-j1"], isolation.token_env(env, token), ws, ws / "tests.log",
                   TESTS_TIMEOUT_S)
    finally:
        isolation.kill_run(token)
    results = ws / "build" / "test_results"
    said = subprocess.run(["catkin_test_results", str(results)], env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, universal_newlines=True, timeout=60)
    summary = next((line for line in said.stdout.splitlines() if line.startswith("Summary:")), said.stdout.strip())
    counts = {kind: int(n) for n, kind in re.findall(r"(\d+) (tests|errors|failures|skipped)", summary)}
    files = len(list(results.rglob("rostest-*.xml")))
    ok = said.returncode == 0 and counts.get("tests", 0) > 0 and not counts.get("errors") and not counts.get("failures")
    return Tests(ok, summary, counts, files, junit_failures(results), time.monotonic() - start)


# --- 3. turtle_tf2's demo against our turtlesim ----------------------------------------------

class Demo(NamedTuple):
    flavour: str
    launch: str
    ok: bool
    reason: str
    samples: List[list]
    seconds: float


def demo(flavour: str, launch: str, env: Dict[str, str], probe: Sequence[str]) -> Demo:
    """turtle_tf2's `launch` against our turtlesim on a private master, measured by the `probe`
    command (a node printing the samples as JSON: tests/e2e/tutorials_probe.py)."""
    from course_testkit.master import PrivateMaster, system_state
    from course_checks.nodes import NodeProcess
    from course_checks.waiting import wait_for

    start = time.monotonic()
    with PrivateMaster(env=env, timeout=START_TIMEOUT_S) as master:
        # No terminal: turtle_teleop_key says so and exits; the probe drives turtle1 instead.
        roslaunch = NodeProcess(["roslaunch", "turtle_tf2", launch], stdin=subprocess.DEVNULL, env=master.env,
                                log_path=str(master.home / "roslaunch.log"))
        master.nodes.append(roslaunch)
        def ours_up() -> bool:  # only our turtlesim has ~snapshot
            services = (system_state(master.uri) or [[], [], []])[2]
            return any(name.endswith("/snapshot") for name, _ in services)

        wait_for(lambda: ours_up() or not roslaunch.running(), START_TIMEOUT_S, 0.2)
        if not ours_up() or not roslaunch.running():
            return Demo(flavour, launch, False, "our turtlesim (its ~snapshot service) did not come up:\n"
                        + roslaunch.output()[-2000:], [], time.monotonic() - start)
        measured = subprocess.run(list(probe), env=master.env,
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                                  timeout=START_TIMEOUT_S + DRIVE_S + FOLLOW_S + 60)
        log = roslaunch.output()
    try:
        result = json.loads(measured.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        result = {"error": "the probe said: %s" % (measured.stdout + measured.stderr)[-2000:]}
    samples = result.get("samples", [])
    reason = result.get("error", "") or judge(samples)
    if reason:
        reason += "\n" + log[-2000:]
    return Demo(flavour, launch, not reason, reason, samples, time.monotonic() - start)


def judge(samples: List[list]) -> str:
    """Why the samples do not show turtle2 following turtle1 ("" when they do)."""
    after = [s for s in samples if s[0] in ("follow", "end")]
    driven = [s for s in samples if s[0] == "drive"]
    if not after or not driven:
        return "too few samples"
    farthest = max(s[6] for s in driven + after[:2])
    moved = math.hypot(after[-1][4] - after[0][4], after[-1][5] - after[0][5])
    if farthest < MOVED_AWAY_M:
        return "turtle1's drive took it only %.2f m from turtle2" % farthest
    if after[-1][6] > FOLLOWED_M or moved < 1.0:
        return "turtle2 did not follow: %.2f m from turtle1 at the end, having moved %.2f m" % (after[-1][6], moved)
    return ""


def follow_table(samples: List[list]) -> List[str]:
    """The samples after the catch-up, one a second: time since the drive started, both poses, distance."""
    kept = [s for s in samples if s[0] != "catch-up"]
    if not kept:
        return []
    t0 = kept[0][1]
    rows, next_t = ["    t (s)  phase   turtle1 (x, y)   turtle2 (x, y)   distance (m)"], 0.0
    for phase, t, x1, y1, x2, y2, d in kept:
        if t - t0 >= next_t - 1e-6 or phase == "end":
            rows.append("    %5.1f  %-6s  (%5.2f, %5.2f)   (%5.2f, %5.2f)   %5.2f" % (t - t0, phase, x1, y1, x2, y2, d))
            next_t = math.floor(t - t0) + 1.0
    return rows


# --- the whole check --------------------------------------------------------------------------

def options(tutorials: str, args: Sequence[str]) -> argparse.Namespace:
    """The suite's options: the folder holding TREES, and TUTORIALS_CHECK_ARGS' words."""
    parser = argparse.ArgumentParser(prog="make tutorials-check TUTORIALS=DIR TUTORIALS_CHECK_ARGS=",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--course", type=Path, default=CHECKOUT / "catkin_ws" / "devel" / "setup.bash",
                        help="the course workspace's setup.bash (default: this checkout's devel space)")
    parser.add_argument("--work", type=Path, help="the overlay workspace (default: a temporary folder)")
    parser.add_argument("--keep", action="store_true", help="keep the overlay workspace")
    parser.add_argument("--skip-tests", action="store_true")
    parser.add_argument("--skip-demo", action="store_true")
    opts = parser.parse_args(list(args))
    opts.tutorials = Path(tutorials)
    return opts


def missing(opts: argparse.Namespace) -> str:
    """Why the suite cannot start ('' when it can): a tree not in the folder, the course not built."""
    absent = [t for t in TREES if not (opts.tutorials / t / "").is_dir()]
    if absent:
        return "no %s in %s" % (", ".join(absent), opts.tutorials)
    return "" if opts.course.is_file() else "%s does not exist: make build first" % opts.course

