"""Run every package's rostest files (src/*/test/*.test and the reference solutions'
solutions/*/test/*.test), each with its own master.

They run through course_checks.rostest_runner, the same runner and pass rule the grader uses
(exit code 0 and JUnit XML with at least one test and no failure), so they never touch a
roscore the user may have running. A failing rostest shows its checks' messages and the end of
its output in the pytest report.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from course_checks.rostest_runner import run_rostest

ROOT = Path(__file__).resolve().parents[1]
TEST_FILES = sorted(ROOT.glob("src/*/test/*.test")) + sorted(ROOT.glob("solutions/*/test/*.test"))
TIMEOUT_S = 240
OUTPUT_TAIL_LINES = 80


@pytest.mark.parametrize("test_file", TEST_FILES, ids=lambda p: "%s/%s" % (p.parts[-3], p.name))
def test_rostest(test_file: Path, tmp_path: Path) -> None:
    result = run_rostest(test_file.parts[-3], test_file.name, results_dir=str(tmp_path), timeout=TIMEOUT_S)
    tail = "\n".join(result.output.splitlines()[-OUTPUT_TAIL_LINES:])
    assert result.passed, "rostest %s failed:\n%s\n--- output (end) ---\n%s" % (test_file.name, result.summary(), tail)
