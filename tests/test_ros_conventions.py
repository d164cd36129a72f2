"""The workspace passes the checks a ROS maintainer runs on packages:

- catkin_lint (PyPI) finds no problem at its default level (0 errors, 0 warnings);
- roslaunch-check (roslaunch's own checker, `rosrun roslaunch roslaunch-check`) passes on every
  launch file: every package, node type and included file it names can be found;
- every package declares what its Python code imports, so that rosdep and the install space
  see the same dependencies the code has (mujoco_gazebo needs numpy and mujoco, ...).

No master is needed: these read files, as the tools do.
"""
from __future__ import annotations

import ast
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from typing import Dict, Iterator, List, Set, Tuple

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC = os.path.join(ROOT, "src")
CATKIN_LINT = os.path.join(ROOT, ".venv", "bin", "catkin_lint")

# Python modules that are not catkin packages of the same name -> their rosdep key.
ROSDEP_KEYS = {
    "numpy": "python3-numpy",
    "mujoco": "python3-mujoco",  # PyPI only: tools/rosdep.yaml maps the key to pip
    "PyQt5": "python3-pyqt5",
    "yaml": "python3-yaml",
    "matplotlib": "python3-matplotlib",
    "hypothesis": "python3-hypothesis",
    "pytest": "python3-pytest",
    "rospkg": "python3-rospkg",
    "catkin_pkg": "python3-catkin-pkg",
    "selenium": "python3-selenium",
}
# ROS packages whose Python module has the package's name (Debian's ROS, or ours).
ROS_MODULES = {"rospy", "rosgraph", "roslib", "roslaunch", "rostest", "rosnode", "rosservice",
               "rostopic", "rosbag", "rosmsg", "tf", "tf2_ros", "actionlib", "genpy", "catkin",
               "topic_tools", "rosunit", "message_filters"}


def packages() -> Dict[str, str]:
    """name -> folder of every package under src/."""
    found = {}
    for entry in sorted(os.listdir(SRC)):
        manifest = os.path.join(SRC, entry, "package.xml")
        if os.path.isfile(manifest):
            found[ET.parse(manifest).getroot().findtext("name")] = os.path.join(SRC, entry)
    return found


def declared(folder: str) -> Tuple[Set[str], Set[str]]:
    """(run dependencies, every dependency) of a package.xml (format 2)."""
    run_tags = {"depend", "exec_depend", "run_depend"}
    run, every = set(), set()
    for element in ET.parse(os.path.join(folder, "package.xml")).getroot():
        if element.tag.endswith("depend") and element.text:
            every.add(element.text.strip())
            if element.tag in run_tags:
                run.add(element.text.strip())
    return run, every


def python_modules_of(pkgs: Dict[str, str]) -> Dict[str, str]:
    """importable module -> the package that provides it: message packages under their own
    name, and each package's src/<module>/ (catkin_python_setup)."""
    modules = {name: name for name in pkgs}
    for name, folder in pkgs.items():
        src = os.path.join(folder, "src")
        if os.path.isdir(src):
            for entry in os.listdir(src):
                if os.path.isfile(os.path.join(src, entry, "__init__.py")):
                    modules[entry] = name
    return modules


def python_files(folder: str) -> Iterator[Tuple[str, bool]]:
    """(path, is test code) of every Python file and #!python script of a package."""
    for root, dirs, files in os.walk(folder):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for name in files:
            path = os.path.join(root, name)
            if name == "setup.py" and root == folder:
                continue  # catkin's own build step
            if not name.endswith(".py"):
                with open(path, "rb") as f:
                    first = f.readline()
                if not (first.startswith(b"#!") and b"python" in first):
                    continue
            rel = os.path.relpath(path, folder)
            yield path, rel.split(os.sep)[0] == "test"


def imports(path: str) -> Set[str]:
    """Top-level names of the absolute imports in one file."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
    return names - set(sys.stdlib_module_names)


def test_catkin_lint_finds_nothing():
    if not os.access(CATKIN_LINT, os.X_OK):
        pytest.fail("catkin_lint is missing from the venv: run `make deps` (requirements.txt lists it)")
    result = subprocess.run([CATKIN_LINT, "-W1", "src"], cwd=os.path.join(ROOT, "catkin_ws"),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    assert "found 0 problems" in result.stdout and result.returncode == 0, result.stdout


def launch_files() -> List[str]:
    return sorted(os.path.join(root, name) for root, _, files in os.walk(SRC)
                  for name in files if name.endswith(".launch"))


@pytest.mark.parametrize("launch", launch_files(), ids=lambda p: os.path.relpath(p, SRC))
def test_roslaunch_check_passes(launch):
    # The same function roslaunch-check calls; in-process, it checks all 15 files in ~1 s.
    from roslaunch import rlutil
    error = rlutil.check_roslaunch(launch)
    assert error is None, "roslaunch-check %s: %s" % (os.path.relpath(launch, SRC), error)


def undeclared_imports() -> List[str]:
    pkgs = packages()
    providers = python_modules_of(pkgs)
    problems = []
    for name, folder in pkgs.items():
        run, every = declared(folder)
        for path, is_test in python_files(folder):
            for module in sorted(imports(path)):
                key = providers.get(module) or ROSDEP_KEYS.get(module) \
                    or (module if module in ROS_MODULES or module.endswith(("_msgs", "_srvs")) else None)
                rel = os.path.relpath(path, SRC)
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


def test_the_import_check_sees_a_missing_dependency(tmp_path, monkeypatch):
    """The check above could pass by reading nothing: a package importing numpy without
    declaring it must be reported."""
    pkg = tmp_path / "src" / "lonely"
    (pkg / "nodes").mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="2"><name>lonely</name>'
                                     '<exec_depend>rospy</exec_depend></package>')
    (pkg / "nodes" / "talk").write_text("#!/usr/bin/env python3\nimport rospy\nimport numpy\n")
    monkeypatch.setattr(sys.modules[__name__], "SRC", str(tmp_path / "src"))
    assert undeclared_imports() == [
        "lonely/nodes/talk imports numpy: package.xml lacks <exec_depend>python3-numpy</exec_depend>"]


def test_every_rostest_is_registered():
    """`catkin_make run_tests` runs a package's test/*.test only if its CMakeLists names it; an
    explicit add_rostest line (no file(GLOB), which misses a new file until CMake reruns)."""
    missing = []
    for name, folder in packages().items():
        test_dir = os.path.join(folder, "test")
        if not os.path.isdir(test_dir):
            continue
        with open(os.path.join(folder, "CMakeLists.txt")) as f:
            cmake = f.read()
        for launch in sorted(n for n in os.listdir(test_dir) if n.endswith(".test")):
            if "add_rostest(test/%s)" % launch not in cmake:
                missing.append("%s: CMakeLists.txt lacks add_rostest(test/%s)" % (name, launch))
    assert not missing, "\n".join(missing)
