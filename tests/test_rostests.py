"""Run every package's rostest files (src/*/test/*.test and the reference solution's
courses/robotics_labs/solution/*/test/*.test), and every milestone of the built-in course against
its reference solution (the overlay sourced: checks/NAME.test, or a data milestone's launch as
the grader writes it), each with its own master.

They run through course_checks.rostest_runner, the same runner and pass rule the grader uses
(exit code 0 and JUnit XML with at least one test and no failure), so they never touch a
roscore the user may have running. A failing rostest shows its checks' messages and the end of
its output in the pytest report.

Each run is its own master in a network namespace of its own, and most of a run waits on what
its checks watch (a turtle's drive, a simulator's start), so JOBS of them run at once, as the
grader runs milestones (--jobs): the first test here starts them all, each test then waits for
its own. That changes when a run happens, not what it checks.
"""
from __future__ import annotations

import os
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path
from typing import Dict, Iterator

import pytest

from course_checks.rostest_runner import run_rostest
from course_grader.runner import rostest_of
from course_format import course_file

ROOT = Path(__file__).resolve().parents[1]
TEST_FILES = sorted(ROOT.glob("src/*/test/*.test")) + sorted(ROOT.glob("courses/robotics_labs/solution/*/test/*.test"))
MILESTONES = course_file.load(course_file.builtin_course_dir()).milestones
# A milestone stands in the list as courses/robotics_labs/milestones/<id>: its run is rostest_of's.
MILESTONE_RUNS = {Path(course_file.builtin_course_dir()) / "milestones" / m.name: m for m in MILESTONES}
TIMEOUT_S = 240
OUTPUT_TAIL_LINES = 80
JOBS = int(os.environ.get("COURSE_ROSTEST_JOBS", "3"))


@pytest.fixture(scope="module")
def runs(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Iterator[Dict[Path, Future]]:
    """The run of every rostest file this session selected, all started at once on JOBS threads,
    in TEST_FILES' order; each in a folder of its own under pytest's temporary folders."""
    selected = [item.callspec.params["test_file"] for item in request.session.items
                if getattr(item, "originalname", "") == "test_rostest" and item.module is request.module]
    folder = tmp_path_factory.mktemp("rostests")

    def run(path: Path) -> Future:
        results = folder / ("%s-%s" % (path.parts[-3], path.stem))
        if path not in MILESTONE_RUNS:
            return pool.submit(run_rostest, path.parts[-3], path.name, results_dir=str(results), timeout=TIMEOUT_S)
        results.mkdir(parents=True)
        package, test_file, args = rostest_of(MILESTONE_RUNS[path], str(results))
        return pool.submit(run_rostest, package, test_file, args, results_dir=str(results), timeout=TIMEOUT_S)
    with ThreadPoolExecutor(max_workers=JOBS) as pool:
        futures = {path: run(path) for path in selected}
        try:
            yield futures
        finally:
            for future in futures.values():
                future.cancel()


@pytest.mark.parametrize("test_file", TEST_FILES + sorted(MILESTONE_RUNS),
                         ids=lambda p: "%s/%s" % (p.parts[-3], p.name))
def test_rostest(test_file: Path, runs: Dict[Path, Future]) -> None:
    result = runs[test_file].result()  # each run ends within TIMEOUT_S (run_rostest kills it then)
    tail = "\n".join(result.output.splitlines()[-OUTPUT_TAIL_LINES:])
    assert result.passed, "rostest %s failed:\n%s\n--- output (end) ---\n%s" % (test_file.name, result.summary(), tail)
