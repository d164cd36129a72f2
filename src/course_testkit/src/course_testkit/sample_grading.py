"""A class of sample submissions graded in the background, and each verdict compared with the
sample's expected.json, for every course's sample tests (tests/test_grader_samples.py for the
built-in course; tests/test_wiki_course.py and tests/test_turtle_motions_course.py, through
CourseGrading, for courses/ros_wiki_beginner and courses/turtle_motions).

expected.json: {"<milestone>": {"passed": true}} or {"<milestone>": {"passed": false,
"reason": "<regex>", "cause": "<key>"}}: the regex must match (re.search, re.S) the milestone's
output in the sample's Gradescope results.json; the cause, when given, must be the one it carries.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

from course_checks.nodes import NodeProcess
from course_checks.gitignore import not_ignored_files
from course_testkit.samples import materialise

STOP_TIMEOUT_S = 30.0
MESSAGE_CHARS = 2500


class BackgroundGrading:
    """`rosrun course_grader grade ARGS... --out FOLDER/grades` running from the start, its output
    to a file (a pipe nobody reads yet would fill and stop the grader)."""

    def __init__(self, args: Sequence[str], prefix: str) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix=prefix))
        self.folder.chmod(0o755)  # the sandbox user passes through it to each student's workspace
        self.out = self.folder / "grades"
        self.args = list(args)

    def start(self) -> None:
        self.grader = NodeProcess(["rosrun", "course_grader", "grade"] + self.args + ["--out", str(self.out)],
                                  stdin=subprocess.DEVNULL, log_path=str(self.folder / "grade.log"))

    def finished(self, timeout: float) -> Tuple[Optional[int], str]:
        """Wait for the grader: its exit code (None if still running after `timeout`) and output."""
        return self.grader.wait(timeout), self.grader.output()

    def graded(self, timeout: float) -> Path:
        """Wait for the grader to end well (a failed test otherwise, with its output's end); the
        output folder."""
        returncode, output = self.finished(timeout)
        assert returncode == 0, "the grader %s:\n%s" % (
            "exited with %s" % returncode if returncode is not None else "ran out of time", output[-5000:])
        print(output)
        return self.out

    def stop(self) -> None:
        """At the session's end: Ctrl+C a grader still running (a session cut short), then remove
        its folder."""
        self.grader.stop(STOP_TIMEOUT_S)
        shutil.rmtree(self.folder, ignore_errors=True)


class CourseGrading(BackgroundGrading):
    """One grader run over a course folder's samples, as handed in (a derived one made from its
    derive.json: course_testkit.samples), each graded on the milestones its expected.json names, and
    over its reference solution, graded as a submission on every milestone."""

    def __init__(self, root: Path, course: Path, jobs: int, prefix: str) -> None:
        super().__init__([], prefix)
        self.course = course
        self.samples = course_samples(course)
        self.checkout_before = git_state(root, str(course))
        handed_in = [materialise(s, self.folder / "derived") for s in self.samples]
        self.args = ["--course", str(course), "--only-from", "expected.json", "--jobs", str(jobs)] + [
            str(s) for s in handed_in] + [str(course / "solution")]
        self.start()


def course_samples(course: Path) -> List[Path]:
    """The sample folders of a course folder (those with an expected.json)."""
    return sorted(p.parent for p in (course / "samples").glob("*/expected.json"))


def course_expectations(course: Path, milestones: Sequence[str]) -> List[Tuple[str, str, Dict]]:
    """(sample, milestone, expected) of every sample of the course, then the reference solution's
    (`solution`): every milestone passes."""
    return expectations(course_samples(course)) + [("solution", m, {"passed": True}) for m in milestones]


def without_both_samples(course: Path, milestones: Sequence[str]) -> Dict[str, object]:
    """The milestones that lack a correct or a buggy sample (each with the verdicts its samples
    expect), and any name a sample expects that is no milestone ({} when each has both)."""
    verdicts: Dict[str, set] = {m: set() for m in milestones}
    wrong: Dict[str, object] = {}
    for sample, milestone, expected in expectations(course_samples(course)):
        if milestone not in verdicts:
            wrong["%s names %s" % (sample, milestone)] = "not a milestone of %s" % ", ".join(milestones)
        else:
            verdicts[milestone].add(bool(expected["passed"]))
    wrong.update({m: v for m, v in verdicts.items() if v != {True, False}})
    return wrong


def not_executable_in_git(root: Path, folder: Path) -> List[str]:
    """The Python files under `folder` that git does not keep executable (rosrun finds a node
    without its bit only through catkin_install_python's relay); ["no Python file"] when git holds
    none. The caller skips where `root` is no checkout (not_a_checkout)."""
    listed = subprocess.run(["git", "-C", str(root), "ls-files", "-s", "--", str(folder)], stdout=subprocess.PIPE,
                            text=True, check=True).stdout.splitlines()
    scripts = [line.split("\t", 1) for line in listed if line.endswith(".py")]
    return [path for mode, path in scripts if not mode.startswith("100755")] if scripts else ["no Python file"]


def not_a_checkout(root: Path) -> str:
    """Why `root` is not the top of a git checkout ("" when it is): the course image copies the
    tree without .git (`make docker-check` runs the suite in /course), a machine may lack git."""
    if not shutil.which("git"):
        return "git is not installed"
    top = subprocess.run(["git", "-C", str(root), "rev-parse", "--show-toplevel"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, check=False)
    if top.returncode != 0:
        return "%s is not a git checkout (%s)" % (root, top.stderr.strip())
    if Path(top.stdout.strip()).resolve() != Path(root).resolve():
        return "%s is not a git checkout of its own (it is inside %s)" % (root, top.stdout.strip())
    return ""


def git_state(root: Path, *paths: str) -> str:
    """What `git status` and `git diff` say of the checkout at `root` (of `paths` in it, if given):
    a sample's grading must change neither. Where `root` is no checkout (not_a_checkout), the same
    question is asked of the files themselves: each file its .gitignore does not ignore, with its
    mode and a digest of its content, so a file written, added, removed or made executable still
    shows."""
    if not_a_checkout(root):
        return files_state(root, *paths)

    def git(*args: str) -> str:
        return subprocess.run(["git", "-C", str(root)] + list(args) + (["--"] + list(paths) if paths else []),
                              stdout=subprocess.PIPE, text=True, check=False).stdout
    return git("status", "--porcelain", "--untracked-files=all") + git("diff")


def files_state(root: Path, *paths: str) -> str:
    """Each file under `root` (under `paths` in it, if given) that its .gitignore does not ignore:
    its path, mode and SHA-256 (a link's target), a line each."""
    inside = [str(Path(p).resolve()) for p in paths]
    lines = []
    for rel in sorted(not_ignored_files(str(root))):
        path = Path(root) / rel
        if inside and not any(str(path.resolve()).startswith(p + "/") or str(path.resolve()) == p for p in inside):
            continue
        mode = path.lstat().st_mode
        what = os.readlink(path) if path.is_symlink() else hashlib.sha256(path.read_bytes()).hexdigest()
        lines.append("%o %s %s" % (mode, what, rel))
    return "\n".join(lines)


def expectations(samples: Sequence[Path]) -> List[Tuple[str, str, Dict]]:
    """(sample, milestone, expected) for each milestone each sample's expected.json names."""
    return [(s.name, m, e) for s in samples for m, e in json.loads((s / "expected.json").read_text()).items()]


def tests_of(graded: Path, sample: str) -> Dict[str, Dict]:
    """The sample's results.json tests, by milestone."""
    results = json.loads((graded / sample / "results.json").read_text())
    return {t["name"].split(":", 1)[0]: t for t in results["tests"]}


def verdict_problem(graded: Path, sample: str, milestone: str, expected: Dict) -> str:
    """How the sample's verdict on `milestone` differs from `expected` ("" when it does not)."""
    tests = tests_of(graded, sample)
    if milestone not in tests:
        return "%s: no verdict for %s (graded: %s)" % (sample, milestone, sorted(tests))
    test = tests[milestone]
    output = test["output"][:MESSAGE_CHARS]
    want = "passed" if expected["passed"] else "failed"
    if test["status"] != want:
        return "%s/%s: expected %s, got %s:\n%s" % (sample, milestone, want, test["status"], output)
    if not expected["passed"] and expected.get("reason") and not re.search(expected["reason"], test["output"], re.S):
        return "%s/%s: the reason does not match %r:\n%s" % (sample, milestone, expected["reason"], output)
    cause = test.get("extra_data", {}).get("cause")
    if "cause" in expected and cause != expected["cause"]:
        return "%s/%s: cause %r, expected %r:\n%s" % (sample, milestone, cause, expected["cause"], output)
    return ""
