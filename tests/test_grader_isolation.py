"""The grader in the places it must work, each saying which isolation was in force
(issue "Grade untrusted code", item 4): as an ordinary user (namespaces without a user switch)
and as root where namespaces are refused (a Gradescope container; asked for here with
COURSE_SANDBOX_LEVEL=user). Root with full isolation is what tests/test_grader_samples.py runs.

Each grades the same samples: a correct solution that leaves a signal-deaf helper behind (it
must pass and the helper must not survive), a node that fakes /turtle1/pose (it must fail with
the guard's sentence), a correct solution, and a buggy one whose helper (new session, empty
environment) tries to forge its results.json (it must fail, and the helper must not survive)."""
from __future__ import annotations

import json
import os
import pwd
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Dict, List

import pytest

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = {"bad_fork": ("chatter", True), "attack_fake_pose": ("pose_subscriber", False),
           "lab2_chatter_scripts": ("chatter", True), "attack_forge_results": ("chatter", False)}
ORDINARY_USER = "nobody"
TIMEOUT_S = 600

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="switching users needs root")


@pytest.fixture
def scratch():
    folder = Path(tempfile.mkdtemp(prefix="grader-isolation-"))
    folder.chmod(0o755)
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


def grade(out: Path, prefix: List[str], env: Dict[str, str]) -> str:
    command = prefix + ["rosrun", "course_grader", "grade"] + [str(ROOT / "courses" / "robotics_labs" / "samples" / s)
                                                                for s in SAMPLES]
    command += ["--only", "chatter", "pose_subscriber", "--out", str(out)]
    done = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=TIMEOUT_S, cwd=str(out.parent))
    assert done.returncode == 0, done.stdout[-3000:]
    return done.stdout


def check_verdicts(out: Path, isolation: str) -> None:
    for sample, (milestone, passed) in SAMPLES.items():
        results = json.loads((out / sample / "results.json").read_text())
        assert "isolation: " + isolation in results["output"], results["output"]
        tests = {t["name"].split(":", 1)[0]: t for t in results["tests"]}
        assert tests[milestone]["status"] == ("passed" if passed else "failed"), tests[milestone]["output"][:2000]
    faked = json.loads((out / "attack_fake_pose" / "results.json").read_text())["tests"]
    assert any("publishes /turtle1/pose, which only turtlesim may publish" in t["output"] for t in faked)


def left_running(out: Path) -> List[str]:
    """Processes of the grading still alive: by its output folder in their environment or mounts."""
    marker = str(out).encode()
    left = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            seen = Path("/proc", pid, "environ").read_bytes() + Path("/proc", pid, "mountinfo").read_bytes()
            cmdline = Path("/proc", pid, "cmdline").read_bytes().replace(b"\0", b" ")
        except OSError:
            continue
        if marker in seen:
            left.append("%s %s" % (pid, cmdline.decode(errors="replace")))
    return left


def test_an_ordinary_user_grades_in_namespaces_without_a_user_switch(scratch: Path) -> None:
    entry = pwd.getpwnam(ORDINARY_USER)
    out = scratch / "grades"
    out.mkdir()
    os.chown(out, entry.pw_uid, entry.pw_gid)
    env = dict(os.environ, HOME=str(scratch), USER=ORDINARY_USER, LOGNAME=ORDINARY_USER)
    printed = grade(out, ["setpriv", "--reuid", ORDINARY_USER, "--regid", str(entry.pw_gid), "--clear-groups", "--"],
                    env)
    assert "isolation: namespaces" in printed and "own loopback-only network" in printed
    check_verdicts(out, "namespaces")
    assert not left_running(out)


def test_root_where_namespaces_are_refused_keeps_the_user_switch(scratch: Path) -> None:
    out = scratch / "grades"
    env = dict(os.environ, COURSE_SANDBOX_LEVEL="user")
    printed = grade(out, [], env)
    assert "isolation: user only" in printed
    check_verdicts(out, "user only")
    assert not left_running(out)
    assert not subprocess.run(["pgrep", "-u", "coursesandbox", "-f", str(out)], stdout=subprocess.PIPE).stdout
