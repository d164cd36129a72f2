"""A whole lab in the workbench, driven as JupyterLab drives it: its REST API (the contents API
writes the student's files) and its terminal websocket (the commands the texts type).

One workbench for the module (`make jupyter`'s start-up on a free port, a fresh home); the
student's package is made once (catkin_create_pkg, a talker and a listener, chmod, catkin_make)
and each test then looks at one thing.
"""
from __future__ import annotations

import json
import os
import subprocess
import tempfile

import pytest

from course_checks.nodes import find_executable
from course_testkit import student_lab
from course_testkit.workbench import REFERENCE_MARKERS, Workbench



@pytest.fixture(scope="module")
def bench():
    with Workbench() as workbench:
        yield workbench


@pytest.fixture(scope="module")
def built_chatter(bench):
    """The student's chatter package, made as 002 section 2 says, through the workbench."""
    with bench.terminal() as term:
        student_lab.make_chatter(bench, term)
    return os.path.join(bench.home, "catkin_ws", "src", "chatter")


def test_the_overlay_is_made_and_built_on_first_start(bench):
    overlay = os.path.join(bench.home, "catkin_ws")
    assert os.path.isdir(os.path.join(overlay, "src"))
    with open(os.path.join(overlay, "devel", "_setup_util.py")) as f:
        chained = f.read()
    course_devel = os.path.join(os.path.dirname(os.path.realpath(find_executable("course_workbench", "workbench"))),
                                "..", "..", "..", "catkin_ws", "devel")
    assert os.path.realpath(course_devel) in chained, "the overlay is not chained on the course workspace"
    assert "solutions_ws" not in chained


def test_a_terminal_is_bash_with_the_course_and_the_overlay_and_no_reference(bench):
    with bench.terminal() as term:
        code, said = term.run('echo "shell=$0"; pwd; echo "$ROS_PACKAGE_PATH"; command -v course-check; '
                              'python3 -c "import rospy; print(\'rospy ok\')"; rospack find turtlesim')
        assert code == 0, said
        assert "shell=/bin/bash" in said or "shell=bash" in said
        assert bench.home + "\n" in said  # terminals open in the student's home
        assert os.path.join(bench.home, "catkin_ws", "src") in said
        assert "rospy ok" in said and "/course_workbench/bin/course-check" in said
        # every folder list of the terminal, and the reference packages by name
        code, paths = term.run('for v in PATH ROS_PACKAGE_PATH PYTHONPATH CMAKE_PREFIX_PATH LD_LIBRARY_PATH '
                               'PKG_CONFIG_PATH ROS_ROOT; do echo "$v=${!v}"; done')
        assert code == 0
        assert not [m for m in REFERENCE_MARKERS if m in paths + ":"], paths
        for reference in ("my_chatter", "turtle_patrol", "pkg_tf"):
            code, said = term.run("rospack find %s" % reference)
            assert code != 0 and "not found" in said, said


def test_catkin_make_in_the_terminal_makes_the_package_found_in_a_new_terminal(bench, built_chatter):
    with bench.terminal() as term:
        code, said = term.run("rospack find chatter && ls -l $(rospack find chatter)/scripts")
    assert code == 0, said
    assert built_chatter in said
    assert said.count("-rwx") == 2, said  # chmod +x, as the text says
    with bench.terminal() as term:  # the texts' own `source devel/setup.bash` works too
        code, said = term.run("cd ~/catkin_ws && source devel/setup.bash && rospack find chatter")
    assert code == 0 and built_chatter in said, said


def test_the_self_check_passes_the_students_package(bench, built_chatter):
    with bench.terminal() as term:
        code, said = term.run("course-check", timeout=student_lab.CHECK_TIMEOUT_S)
    assert code == 0, said
    assert student_lab.PASSED in said
    assert "isolation: " in said
    report = os.path.join(bench.home, "course-check", "report.html")
    assert os.path.isfile(report) and report in said
    status, data, _ = bench.request("GET", "/api/contents/course-check/report.html")
    assert status == 200 and "chatter" in json.loads(data)["content"]  # JupyterLab serves it


def test_the_self_check_fails_a_buggy_package_with_its_reason_as_the_ta_would(bench, built_chatter):
    """A talker on the wrong topic, in another folder of the student's: the self-check says why it
    fails, and the TA's `grade` of the same files gives the same verdict."""
    with bench.terminal() as term:
        buggy = student_lab.make_buggy_copy(bench, term)
        code, said = term.run("course-check ~/%s --out ~/buggy-check" % buggy, timeout=student_lab.CHECK_TIMEOUT_S)
    assert code == 1, said
    assert student_lab.FAILED in said
    assert student_lab.BUGGY_REASON in said
    with open(os.path.join(bench.home, "buggy-check", "buggy", "results.json")) as f:
        mine = [(t["name"], t["status"], t["output"].split("\n\n")[0]) for t in json.load(f)["tests"]]
    with tempfile.TemporaryDirectory() as grades:
        os.chmod(grades, 0o755)
        done = subprocess.run(["rosrun", "course_grader", "grade", os.path.join(bench.home, "buggy"),
                               "--out", grades], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=240, check=False)
        assert done.returncode == 0, done.stdout[-3000:]
        with open(os.path.join(grades, "buggy", "results.json")) as f:
            ta = [(t["name"], t["status"], t["output"].split("\n\n")[0]) for t in json.load(f)["tests"]]
    assert mine == ta
