#!/usr/bin/env python3
"""`make flake-hunt K=10`: run the whole suite K times in a row and report failures per test.

Usage: python3 tools/flake_hunt.py [--until-fail] [--out DIR] [--all] K [pytest args...]   (a sourced workspace)

Each run is `python3 -m pytest` from the repository root in the sourced workspace (as `make
test` runs it), with its JUnit XML and its output kept in DIR (default output/flake-hunt/<time>/).
The report lists each run (counts, exit code, wall time) and each test that failed at least once
(runs, failures, the first failure's message line), then the totals. Exit code 1 if any run
failed. A flake is hunted at its cause: this tool reruns to find and describe it, never to hide it.
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path
from typing import List, Sequence

from course_testkit import flakes

ROOT = Path(__file__).resolve().parents[1]
SETUP = ROOT / "catkin_ws" / "devel" / "setup.bash"

# Source the workspace (never under set -u), then pytest from the root, as `make test` does.
PYTEST_IN_WORKSPACE = 'source "$1" && cd "$2" && exec python3 -m pytest "${@:3}"'


def run_suite(index: int, out_dir: Path, pytest_args: Sequence[str]) -> flakes.Run:
    xml_path = out_dir / ("run-%02d.xml" % index)
    log_path = out_dir / ("run-%02d.log" % index)
    command = ["bash", "-c", PYTEST_IN_WORKSPACE, "flake-hunt", str(SETUP), str(ROOT),
               "--junitxml=%s" % xml_path] + list(pytest_args)
    started = time.monotonic()
    with open(log_path, "wb") as log:
        returncode = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT).returncode
    return flakes.Run(index, time.monotonic() - started, returncode, flakes.read_outcomes(str(xml_path)))


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0], allow_abbrev=False,
                                     usage="%(prog)s [--until-fail] [--out DIR] [--all] K [pytest args...]")
    parser.add_argument("runs", type=int, metavar="K", help="how many runs of the suite")
    parser.add_argument("--until-fail", action="store_true", help="stop after the first run that fails")
    parser.add_argument("--out", type=Path, help="where the JUnit XML and logs go")
    parser.add_argument("--all", action="store_true", help="list every test, not only those that failed")
    args, pytest_args = parser.parse_known_args(argv)
    if args.runs < 1:
        parser.error("K must be at least 1")
    args.pytest_args = [a for a in pytest_args if a != "--"]
    return args


def main(argv: Sequence[str]) -> int:
    args = parse_args(argv)
    out_dir = args.out or ROOT / "output" / "flake-hunt" / time.strftime("%Y%m%d-%H%M%S")
    out_dir.mkdir(parents=True, exist_ok=True)
    print("flake hunt: %d runs of `python3 -m pytest %s`; JUnit XML and logs in %s"
          % (args.runs, " ".join(args.pytest_args), out_dir), flush=True)
    runs: List[flakes.Run] = []
    for index in range(1, args.runs + 1):
        runs.append(run_suite(index, out_dir, args.pytest_args))
        print(flakes.run_line(runs[-1], args.runs), flush=True)
        if args.until_fail and runs[-1].failed:
            break
    text = flakes.report(runs, show_all=args.all)
    (out_dir / "report.txt").write_text(text + "\n")
    print(text)
    return 1 if flakes.any_failure(runs) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
