"""`course-lint` on real courses (docs/course_lint.md): the built-in course's chatter milestone
kills mutants of its reference; a mutant of a line the reference never runs is `not run` and is
not graded (measured by the probe beside the reference: course_lint.ran); an `equivalent`
annotation moves a survivor out of the score, and one that names a killed mutant is an error at
its line (exit 2); a course whose reference fails its milestone makes it exit 1, and a course file
with an error exit 2. Each grading is a real grader run (catkin builds and rostests), so the
operators are limited to a few; the two gradings start as soon as the session knows these tests
will run (start_early, called by the root conftest.py), so they overlap the rest of a suite."""
from __future__ import annotations

import json
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
SUMMARY = re.compile(r"^mutants: (\d+) made, (\d+) killed, (\d+) survived, (\d+) equivalent, (\d+) not run$")
WAIT_S = 600  # a lint run: the reference, then each mutant, one grading at a time beside the suite
# A function of chatter's publisher that nothing calls: its publish is a site of publish_removed and
# exit_after_one, whose mutants there are not run.
NEVER_CALLED = '''

def shout(pub) -> None:
    """Never called: course-lint's test (tests/test_course_lint.py) adds it to the reference."""
    pub.publish("HELLO")
'''
# rate_div10_1 survives (section 2 fixes no rate); no_spin_1, the listener without rospy.spin(), is killed.
ANNOTATIONS = """    equivalent:
      rate_div10_1: "section 2 fixes no rate"
      no_spin_1: "wrongly named: the listener stops at once"
"""


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
        code = self.proc.wait(WAIT_S)
        return subprocess.CompletedProcess(self.proc.args, code, self.out.read_text(), self.err.read_text())

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def course_copy(folder: Path, name: str) -> Path:
    """The built-in course's file and checks, with chatter's reference alone (in `name`/solution)."""
    course = folder / name
    course.mkdir()
    text = (BUILTIN / "course.yaml").read_text()
    text = re.sub(r"(?m)^solution: .*$", "solution: solution", text)
    text = re.sub(r"(?m)^    equivalent:\n(?:      .*\n)+", "", text)  # the tests write their own
    (course / "course.yaml").write_text(re.sub(r"(?m)^samples: .*\n", "", text))
    shutil.copytree(str(BUILTIN / "checks"), str(course / "checks"))  # a course's checks are in its folder
    shutil.copytree(str(ROOT / "courses" / "robotics_labs" / "solution" / "chatter"), str(course / "solution" / "chatter"), symlinks=True)
    return course


def broken_course(folder: Path) -> Path:
    """The built-in course with one milestone's reference that fails it: chatter publishing elsewhere."""
    course = course_copy(folder, "course")
    pub = course / "solution" / "chatter" / "src" / "example_pub.py"
    pub.write_text(pub.read_text().replace('"chatter_talk"', '"chatter_elsewhere"'))
    return course


def annotated_course(folder: Path) -> Path:
    """The built-in course with chatter's publisher holding a function nothing calls, and its
    milestone two `equivalent` annotations: one of a survivor, one of a killed mutant."""
    course = course_copy(folder, "annotated")
    pub = course / "solution" / "chatter" / "src" / "example_pub.py"
    text = pub.read_text()
    pub.write_text(text.replace('\n\nif __name__ == "__main__":', NEVER_CALLED + '\n\nif __name__ == "__main__":', 1))
    yaml = course / "course.yaml"
    chatter = "    packages: [chatter]\n    check: chatter.test\n"
    assert chatter in yaml.read_text()
    yaml.write_text(yaml.read_text().replace(chatter, chatter + ANNOTATIONS, 1))
    return course


RUNS = pytest.StashKey[Dict[str, LintRun]]()
FOLDER = pytest.StashKey[Path]()


def start_early(config: pytest.Config) -> None:
    folder = Path(tempfile.mkdtemp(prefix="course-lint-test-"))
    # one run at a time each: they overlap the suite and the other background gradings
    runs = {"chatter": LintRun(folder, "chatter", str(annotated_course(folder)), "--only", "chatter", "--jobs", "1",
                               "--operators", "exit_after_one,no_spin,publish_removed,rate_div10",
                               "--json", str(folder / "chatter.json")),
            "broken": LintRun(folder, "broken", str(broken_course(folder)), "--only", "chatter", "--jobs", "1",
                              "--operators", "no_spin")}
    config.stash[RUNS] = runs
    config.stash[FOLDER] = folder

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


def test_chatter_mutants_get_their_statuses(runs, request):
    """The reference passes; the mutants of shout(), which nothing calls, are not run and not graded;
    rate_div10_1 survives and its annotation makes it equivalent, out of K/N; no_spin_1 is killed, so
    its annotation is an error at its line, and the command exits 2."""
    done = runs["chatter"].result()
    assert done.returncode == 2, done.stdout + done.stderr
    assert "REFERENCE FAILS" not in done.stdout
    table = json.loads((request.config.stash[FOLDER] / "chatter.json").read_text())
    mutants = {m["name"]: m for m in table["milestones"][0]["mutants"]}
    pub = Path(table["root"]) / "solution" / "chatter" / "src" / "example_pub.py"
    shout = 1 + pub.read_text().splitlines().index('    pub.publish("HELLO")')
    assert {name: (m["status"], m["graded"], m["why"]) for name, m in mutants.items()
            if name in ("publish_removed_2", "exit_after_one_2")} == {
        "publish_removed_2": ("not run", False, "line %d never ran" % shout),
        "exit_after_one_2": ("not run", False, "line %d never ran" % shout)}, done.stdout
    assert (mutants["rate_div10_1"]["status"], mutants["rate_div10_1"]["why"]) == ("equivalent", "section 2 fixes no rate")
    assert mutants["no_spin_1"]["status"] == "killed" and mutants["no_spin_1"]["graded"]
    assert all(m["graded"] for m in mutants.values() if m["status"] != "not run")
    # the score counts the killed and the survivors only
    killed, survived = table["killed"], table["survived"]
    last = LAST_LINE.match(lines(done)[-1])
    assert last and (int(last.group(1)), int(last.group(2))) == (killed, killed + survived), done.stdout
    assert SUMMARY.match(lines(done)[-2]).groups() == tuple(str(n) for n in (
        len(mutants), killed, survived, table["equivalent"], table["not_run"])), done.stdout
    assert (table["equivalent"], table["not_run"], killed) == (1, 2, 3), done.stdout
    first = lines(done)[0]
    assert first.startswith("chatter  %d/%d killed  survivors: " % (killed, killed + survived)), first
    assert "  equivalent: rate_div10_1 (chatter/src/example_pub.py:" in first and "  not run: exit_after_one_2 (" in first
    # the annotation of a killed mutant: FILE:LINE: FIELD on stderr
    yaml_line = 1 + next(i for i, line in enumerate((Path(table["root"]) / "course.yaml").read_text().splitlines())
                         if line.strip().startswith("no_spin_1:"))
    assert re.search(r"course\.yaml:%d: milestones\[\d+\]\.equivalent\.no_spin_1: names no surviving mutant: "
                     r"no_spin_1 is killed" % yaml_line, done.stderr), done.stderr


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
