"""The Gradescope autograder: `make_autograder` writes the zip; its run_autograder, run in a temp
folder laid out like Gradescope's (/autograder/source, submission, results; relocated through
AUTOGRADER_ROOT), grades one good and one bad submission into results.json in Gradescope's format
(gradescope-autograders.readthedocs.io, "Autograder Specifications")."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
COURSE_SETUP = ROOT / "catkin_ws" / "devel" / "setup.bash"
VISIBILITY = {"hidden", "after_due_date", "after_published", "visible"}


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("zip") / "autograder.zip"
    subprocess.run(["rosrun", "course_grader", "make_autograder", "--out", str(out), "--only", "chatter"],
                   check=True, stdout=subprocess.PIPE, timeout=120)
    return out


def test_zip_has_gradescopes_entry_points_at_its_root(autograder_zip: Path, tmp_path: Path) -> None:
    with zipfile.ZipFile(autograder_zip) as zf:
        names = set(zf.namelist())
        assert {"setup.sh", "run_autograder", "Makefile", "milestones.txt"} <= names
        assert "src/course_grader/package.xml" in names and not any(n.startswith("courses/robotics_labs/samples/") for n in names)
        for entry in ("setup.sh", "run_autograder"):
            assert (zf.getinfo(entry).external_attr >> 16) & 0o111, "%s is not executable" % entry
        assert zf.read("milestones.txt").decode().split() == ["chatter"]
        zf.extract("setup.sh", tmp_path)
    assert subprocess.run(["bash", "-n", str(tmp_path / "setup.sh")]).returncode == 0


def _gradescope_layout(base: Path, autograder_zip: Path, submission: Path) -> Path:
    root = base / "autograder"
    (root / "results").mkdir(parents=True)
    with zipfile.ZipFile(autograder_zip) as zf:
        zf.extractall(root / "source")
    for entry in ("setup.sh", "run_autograder"):
        os.chmod(root / "source" / entry, 0o755)  # zipfile does not restore modes; unzip does
    shutil.copy(root / "source" / "run_autograder", root / "run_autograder")
    shutil.copytree(submission, root / "submission")
    return root


def _check_format(results: dict) -> None:
    assert isinstance(results["score"], (int, float))
    assert isinstance(results.get("output", ""), str) and results.get("visibility", "visible") in VISIBILITY
    assert results["tests"], "no tests in results.json"
    for test in results["tests"]:
        assert isinstance(test["name"], str) and isinstance(test["output"], str)
        assert isinstance(test["score"], (int, float)) and isinstance(test["max_score"], (int, float))
        assert test["status"] in ("passed", "failed") and test.get("visibility", "visible") in VISIBILITY
    assert results["score"] == sum(t["score"] for t in results["tests"])


def _run_autograder(root: Path) -> dict:
    """run_autograder as Gradescope runs it in `root`: it exits 0 and writes results.json in format."""
    env = dict(os.environ, AUTOGRADER_ROOT=str(root), COURSE_WS_SETUP=str(COURSE_SETUP))
    proc = subprocess.run([str(root / "run_autograder")], cwd=root, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout[-3000:]
    results = json.loads((root / "results" / "results.json").read_text())
    _check_format(results)
    return results


@pytest.mark.parametrize("submission,passed", [
    (ROOT / "courses" / "robotics_labs" / "solution" / "chatter", True),  # our reference package, handed in as a student would
    (ROOT / "courses" / "robotics_labs" / "samples" / "bad_wrong_name", False),
], ids=["good", "bad"])
def test_run_autograder(autograder_zip: Path, tmp_path: Path, submission: Path, passed: bool) -> None:
    root = _gradescope_layout(tmp_path, autograder_zip, submission)
    results = _run_autograder(root)
    [test] = results["tests"]
    assert test["name"].startswith("chatter:")
    assert test["status"] == ("passed" if passed else "failed"), test["output"]
    if not passed:
        assert "expected a catkin package named 'chatter'" in test["output"]


def test_another_course_goes_in_without_its_answers(tmp_path: Path) -> None:
    """`make autograder COURSE=DIR`: the course folder is in the zip (copied under courses/ when it
    lies outside the repository), its solution/ and samples/ are not, and course.txt names it for
    run_autograder; no course folder's answers are in any zip."""
    from course_grader import autograder
    course = tmp_path / "my_course"
    for rel in ("course.yaml", "checks/mine.test", "solution/pkg/package.xml", "samples/good/pkg/package.xml"):
        (course / rel).parent.mkdir(parents=True, exist_ok=True)
        (course / rel).write_text("x")
    out = tmp_path / "autograder.zip"
    autograder.write_zip(str(ROOT), str(out), course=str(course))
    with zipfile.ZipFile(out) as zf:
        names = set(zf.namelist())
        assert {"courses/my_course/course.yaml", "courses/my_course/checks/mine.test"} <= names
        assert zf.read("course.txt").decode().strip() == "courses/my_course"
    assert not [n for n in names if autograder.answer(n)], "answers in the zip"
    assert autograder.answer("courses/ros_wiki_beginner/solution/beginner_tutorials/package.xml")
    assert autograder.answer("courses/any/samples/good/expected.json")
    assert not autograder.answer("courses/any/course.yaml")
    run = (ROOT / "src" / "course_grader" / "autograder" / "run_autograder").read_text()
    assert "course.txt" in run and "--course" in run


def test_run_autograder_of_another_course(tmp_path: Path) -> None:
    """`make autograder COURSE=courses/ros_wiki_beginner MILESTONES=pubsub_py`: Gradescope's run grades
    a student's package against that course's milestone, read from the zip's copy of the course."""
    out = tmp_path / "autograder.zip"
    subprocess.run(["rosrun", "course_grader", "make_autograder", "--out", str(out), "--only", "pubsub_py",
                    "--course", str(ROOT / "courses" / "ros_wiki_beginner")],
                   check=True, stdout=subprocess.PIPE, timeout=120)
    with zipfile.ZipFile(out) as zf:
        assert zf.read("course.txt").decode().strip() == "courses/ros_wiki_beginner"
        assert not [n for n in zf.namelist() if "/solution/" in n or "/samples/" in n]
    sample = ROOT / "courses" / "ros_wiki_beginner" / "samples" / "good_pubsub_py_classes"
    root = _gradescope_layout(tmp_path, out, sample)
    results = _run_autograder(root)
    [test] = results["tests"]
    assert test["name"].startswith("pubsub_py:") and test["status"] == "passed", test["output"]
