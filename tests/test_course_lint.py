"""`course-lint` on real courses: the built-in course's chatter milestone kills mutants of its
reference, a course whose reference fails its milestone makes it exit 1, and a course file with
an error exit 2 (docs/course_lint.md). Each grading is a real grader run (catkin builds and
rostests), so the operators are limited to a few; the two gradings start as soon as the session
knows these tests will run (start_early, called by the root conftest.py), so they overlap the rest
of a suite."""
from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Dict, List

import pytest

ROOT = Path(__file__).resolve().parents[1]
BUILTIN = ROOT / "courses" / "robotics_labs"
LAST_LINE = re.compile(r"^mutants killed (\d+)/(\d+)$")


def course_lint(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(["rosrun", "course_lint", "course-lint"] + list(args), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True, timeout=300, check=False)


class LintRun:
    """`course-lint ARGS...` in the background, its output to files, waited for by a test."""

    def __init__(self, folder: Path, name: str, *args: str) -> None:
        self.out, self.err = folder / (name + ".out"), folder / (name + ".err")
        with open(self.out, "w") as out, open(self.err, "w") as err:
            self.proc = subprocess.Popen(["rosrun", "course_lint", "course-lint"] + list(args), stdout=out,
                                         stderr=err, stdin=subprocess.DEVNULL, text=True, start_new_session=True)

    def result(self) -> subprocess.CompletedProcess:
        code = self.proc.wait(300)
        return subprocess.CompletedProcess(self.proc.args, code, self.out.read_text(), self.err.read_text())

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def broken_course(folder: Path) -> Path:
    """The built-in course with one milestone's reference that fails it: chatter publishing elsewhere."""
    course = folder / "course"
    course.mkdir()
    text = (BUILTIN / "course.yaml").read_text()
    text = re.sub(r"(?m)^solution: .*$", "solution: solution", text)
    (course / "course.yaml").write_text(re.sub(r"(?m)^samples: .*\n", "", text))
    shutil.copytree(str(BUILTIN / "checks"), str(course / "checks"))  # a course's checks are in its folder
    shutil.copytree(str(ROOT / "courses" / "robotics_labs" / "solution" / "chatter"), str(course / "solution" / "chatter"), symlinks=True)
    pub = course / "solution" / "chatter" / "src" / "example_pub.py"
    pub.write_text(pub.read_text().replace('"chatter_talk"', '"chatter_elsewhere"'))
    return course


RUNS = pytest.StashKey[Dict[str, LintRun]]()


def start_early(config: pytest.Config) -> None:
    folder = Path(tempfile.mkdtemp(prefix="course-lint-test-"))
    # one run at a time each: they overlap the suite and the other background gradings
    runs = {"chatter": LintRun(folder, "chatter", str(BUILTIN), "--only", "chatter", "--jobs", "1", "--operators",
                               "topic_renamed,exit_after_one,no_spin,publish_removed"),
            "broken": LintRun(folder, "broken", str(broken_course(folder)), "--only", "chatter", "--jobs", "1",
                              "--operators", "no_spin")}
    config.stash[RUNS] = runs

    def clean_up() -> None:
        for run in runs.values():
            run.stop()
        shutil.rmtree(folder, ignore_errors=True)
    config.add_cleanup(clean_up)


@pytest.fixture(scope="module")
def runs(request: pytest.FixtureRequest) -> Dict[str, LintRun]:
    if RUNS not in request.config.stash:  # this module was not known to be selected at collection
        start_early(request.config)
    return request.config.stash[RUNS]


def lines(done: subprocess.CompletedProcess) -> List[str]:
    return done.stdout.strip().splitlines()


def test_chatter_reference_passes_and_mutants_are_killed(runs):
    done = runs["chatter"].result()
    assert done.returncode == 0, done.stdout + done.stderr
    last = LAST_LINE.match(lines(done)[-1])
    assert last, lines(done)
    killed, total = int(last.group(1)), int(last.group(2))
    assert killed >= 3 and total == 5, done.stdout
    assert lines(done)[0].startswith("chatter  %d/%d killed  survivors: " % (killed, total)), done.stdout
    assert "REFERENCE FAILS" not in done.stdout


def test_a_reference_that_fails_its_milestone_exits_1(runs):
    done = runs["broken"].result()
    assert done.returncode == 1, done.stdout + done.stderr
    assert lines(done)[0].startswith("chatter  REFERENCE FAILS  "), done.stdout
    assert "the reference fails chatter: " in done.stdout and "/chatter_talk" in done.stdout
    assert LAST_LINE.match(lines(done)[-1]), done.stdout


def test_a_course_file_error_exits_2_and_says_where(tmp_path: Path):
    (tmp_path / "course.yaml").write_text("name: broken\ntitle: Broken\nmilestones:\n  - id: Bad Id\n")
    done = course_lint(str(tmp_path))
    assert done.returncode == 2, done.stdout + done.stderr
    assert "course.yaml:4: milestones[0]" in done.stderr and "Traceback" not in done.stderr
