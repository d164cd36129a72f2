"""A class of sample submissions graded in the background, and each verdict compared with the
sample's expected.json, for every course's sample tests (tests/test_grader_samples.py for the
built-in course, tests/test_wiki_course.py for courses/ros_wiki_beginner).

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
