"""`make tutorials-check TUTORIALS=DIR`: ROS 1's own tutorials as an overlay on the course workspace
(course_testkit.tutorials; docs/noetic_cxx.md). An end-to-end suite (the `e2e` marker: `make test`
leaves it out: the sources are not in the repository, and a run takes a few minutes).

TUTORIALS in the environment names the folder holding ros_tutorials, geometry_tutorials and
common_tutorials (without it the test is skipped); TUTORIALS_CHECK_ARGS the options (--keep,
--work DIR, --skip-tests, --skip-demo, --course SETUP). The overlay is built as the grader builds
a student's packages, its tests run, and turtle_tf2's demos (Python and C++) must drive our
turtlesim: one line per step with its figures, the test passing only when every step passed.
"""
from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from course_checks.isolation import sourced_env
from course_grader.build_errors import summarise
from course_testkit.tutorials import DEMOS, DRIVE_S, SAMPLE_S, build, copy_sources, demo, follow_table, missing, \
    options, run_tests

pytestmark = pytest.mark.e2e
PROBE = [sys.executable, str(Path(__file__).resolve().parent / "tutorials_probe.py")]  # a node of each demo's master


def test_the_tutorials_build_pass_their_tests_and_drive_our_turtlesim():
    if not os.environ.get("TUTORIALS"):
        pytest.skip("TUTORIALS=DIR names the folder of the tutorials' sources (make tutorials-check TUTORIALS=DIR)")
    args = options(os.environ["TUTORIALS"], shlex.split(os.environ.get("TUTORIALS_CHECK_ARGS", "")))
    why = missing(args)
    if why:
        pytest.fail("tutorials-check: %s" % why, pytrace=False)
    started = time.monotonic()
    ws = args.work.resolve() if args.work else Path(tempfile.mkdtemp(prefix="tutorials-check-"))
    ok = True
    try:
        left_out = copy_sources(args.tutorials, ws / "src")
        print("tutorials-check: overlay %s on %s; left out: %s" % (ws, args.course.parent, "; ".join(left_out)),
              flush=True)
        built = build(ws, args.course, summarise)
        print("build: %d packages (%s), %d failed%s, %.1f s" % (
            len(built.packages), " ".join(built.packages), len(built.failed),
            " (%s)" % " ".join(built.failed) if built.failed else "", built.seconds), flush=True)
        if built.reason:
            print("  " + built.reason.replace("\n", "\n  "))
        ok = built.ok
        env = sourced_env(ws / "devel" / "setup.bash") if (ws / "devel" / "setup.bash").exists() else None
        if env is not None and not args.skip_tests:
            tests = run_tests(ws, env)
            print("tests: %s in %d rostest files, %.1f s%s" % (tests.summary, tests.files, tests.seconds,
                                                               "" if tests.ok else ": FAILED"), flush=True)
            for failure in tests.failing:
                print("  failed: " + failure)
            ok = ok and tests.ok
        if env is not None and not args.skip_demo:
            where = subprocess.run(["rospack", "find", "turtle_tf2"], env=env, stdout=subprocess.PIPE,
                                   universal_newlines=True).stdout.strip()
            for flavour, launch in DEMOS:
                shown = demo(flavour, launch, env, PROBE)
                after = [s for s in shown.samples if s[0] != "catch-up"]
                print("demo %s (%s, turtle_tf2 from %s): %s, %.1f s" % (
                    launch, flavour, where, "turtle2 follows turtle1: %.2f m apart after the drive, %.2f m at "
                    "the end" % (max(s[6] for s in after[:int(DRIVE_S / SAMPLE_S) + 2]), after[-1][6])
                    if shown.ok else "FAILED", shown.seconds), flush=True)
                for row in follow_table(shown.samples):
                    print(row)
                if shown.reason:
                    print("  " + shown.reason.replace("\n", "\n  "))
                ok = ok and shown.ok
    finally:
        if args.keep or args.work:
            print("tutorials-check: the overlay is kept in %s" % ws)
        else:
            shutil.rmtree(ws, ignore_errors=True)
    print("tutorials-check: %s in %.1f s" % ("passed" if ok else "FAILED", time.monotonic() - started))
    assert ok, "tutorials-check failed: see its lines above"
