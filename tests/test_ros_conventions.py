"""The workspace passes the checks a ROS maintainer runs on packages:

- catkin_lint (PyPI) finds no problem at its default level (0 errors, 0 warnings);
- roslaunch-check (roslaunch's own checker, `rosrun roslaunch roslaunch-check`) passes on every
  launch file: every package, node type and included file it names can be found;
- every package declares what its Python code imports, so that rosdep and the install space
  see the same dependencies the code has (mujoco_gazebo needs numpy and mujoco, ...).

No master is needed: these read files, as the tools do.
"""
from __future__ import annotations

import os
import subprocess
from typing import List

import pytest

from course_testkit import package_scan as scan

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC = os.path.join(ROOT, "src")
SOLUTIONS = os.path.join(ROOT, "courses", "robotics_labs", "solution")  # the built-in course's reference, an overlay of its own
CATKIN_LINT = os.path.join(ROOT, ".venv", "bin", "catkin_lint")

# Python modules that are not catkin packages of the same name -> their rosdep key.
ROSDEP_KEYS = {
    "numpy": "python3-numpy",
    "mujoco": "python3-mujoco",  # PyPI only: setup/rosdep.yaml maps the key to pip
    "copydetect": "python3-copydetect",  # PyPI only: setup/rosdep.yaml maps the key to pip
    "PyQt5": "python3-pyqt5",
    "yaml": "python3-yaml",
    "jsonschema": "python3-jsonschema",
    "matplotlib": "python3-matplotlib",
    "hypothesis": "python3-hypothesis",
    "coverage": "python3-coverage",
    "pytest": "python3-pytest",
    "rospkg": "python3-rospkg",
    "catkin_pkg": "python3-catkin-pkg",
    "selenium": "python3-selenium",
    "tornado": "python3-tornado",
    "PIL": "python3-pil",
    "bcrypt": "python3-bcrypt",
    "jwt": "python3-jwt",
    "cryptography": "python3-cryptography",
    "lti1p3platform": "python3-lti1p3platform",  # PyPI only: setup/rosdep.yaml maps the key to pip
    # the hub's own venv (.venv-hub): course_hub.auth and course_hub.spawner are imported by JupyterHub there
    "firstuseauthenticator": "python3-jupyterhub-firstuseauthenticator",  # PyPI: setup/rosdep.yaml
    "dockerspawner": "python3-dockerspawner",  # PyPI: setup/rosdep.yaml
    "ltiauthenticator": "python3-jupyterhub-ltiauthenticator",  # PyPI: setup/rosdep.yaml (course_hub.lti)
    "traitlets": "python3-traitlets",
    # the students' JupyterLab venv (.venv-jupyter): course_workbench/venv/singleuser.py runs there
    "jupyterhub": "python3-jupyterhub",  # PyPI: setup/rosdep.yaml
}
# ROS packages whose Python module has the package's name (Debian's ROS, or ours).
ROS_MODULES = {"rospy", "rosgraph", "roslib", "roslaunch", "rostest", "rosnode", "rosservice",
               "rostopic", "rosbag", "rosmsg", "tf", "tf2_ros", "actionlib", "genpy", "genmsg", "catkin",
               "topic_tools", "rosunit", "message_filters"}


def test_catkin_lint_finds_nothing():
    if not os.access(CATKIN_LINT, os.X_OK):
        pytest.fail("catkin_lint is missing from the venv: run `make deps` (requirements.txt lists it)")
    for ws in ("catkin_ws", "solutions_ws"):
        result = subprocess.run([CATKIN_LINT, "-W1", "src"], cwd=os.path.join(ROOT, ws),
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        assert "found 0 problems" in result.stdout and result.returncode == 0, "%s: %s" % (ws, result.stdout)


def launch_files() -> List[str]:
    return sorted(os.path.join(root, name) for top in (SRC, SOLUTIONS) for root, _, files in os.walk(top)
                  for name in files if name.endswith(".launch"))


@pytest.mark.parametrize("launch", launch_files(), ids=lambda p: os.path.relpath(p, ROOT))
def test_roslaunch_check_passes(launch):
    # The same function roslaunch-check calls; in-process, it checks all 15 files in ~1 s.
    from roslaunch import rlutil
    error = rlutil.check_roslaunch(launch)
    assert error is None, "roslaunch-check %s: %s" % (os.path.relpath(launch, ROOT), error)


def undeclared_imports(*srcs: str) -> List[str]:
    pkgs = scan.packages(*(srcs or (SRC, SOLUTIONS)))
    providers = scan.python_modules_of(pkgs)
    problems = []
    for name, folder in pkgs.items():
        run, every = scan.declared(folder)
        for path, is_test in scan.python_files(folder):
            for module in sorted({dotted.split(".")[0] for dotted in scan.imports(path)}):
                key = providers.get(module) or ROSDEP_KEYS.get(module) \
                    or (module if module in ROS_MODULES or module.endswith(("_msgs", "_srvs")) else None)
                rel = os.path.relpath(path, os.path.dirname(folder))
                if key is None:
                    if not is_test:
                        problems.append("%s imports %s, which no package or rosdep key in this "
                                        "test's table provides" % (rel, module))
                elif key != name and key not in (every if is_test else run):
                    tag = "test_depend" if is_test else "exec_depend"
                    problems.append("%s imports %s: package.xml lacks <%s>%s</%s>"
                                    % (rel, module, tag, key, tag))
    return problems


def test_every_import_is_declared():
    problems = undeclared_imports()
    assert not problems, "\n".join(problems)


def test_the_import_check_sees_a_missing_dependency(tmp_path):
    """The check above could pass by reading nothing: a package importing numpy without
    declaring it must be reported."""
    pkg = tmp_path / "src" / "lonely"
    (pkg / "nodes").mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="2"><name>lonely</name>'
                                     '<exec_depend>rospy</exec_depend></package>')
    (pkg / "nodes" / "talk").write_text("#!/usr/bin/env python3\nimport rospy\nimport numpy\n")
    assert undeclared_imports(str(tmp_path / "src")) == [
        "lonely/nodes/talk imports numpy: package.xml lacks <exec_depend>python3-numpy</exec_depend>"]


def test_every_rostest_is_registered():
    """`catkin_make run_tests` runs a package's test/*.test only if its CMakeLists names it; an
    explicit add_rostest line (no file(GLOB), which misses a new file until CMake reruns)."""
    missing = []
    for name, folder in scan.packages(SRC, SOLUTIONS).items():
        test_dir = os.path.join(folder, "test")
        if not os.path.isdir(test_dir):
            continue
        with open(os.path.join(folder, "CMakeLists.txt")) as f:
            cmake = f.read()
        for launch in sorted(n for n in os.listdir(test_dir) if n.endswith(".test")):
            if "add_rostest(test/%s)" % launch not in cmake:
                missing.append("%s: CMakeLists.txt lacks add_rostest(test/%s)" % (name, launch))
    assert not missing, "\n".join(missing)
