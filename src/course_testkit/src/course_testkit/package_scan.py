"""Read a catkin source folder the way the ROS tools do, without building it: the packages, what
each package.xml declares, and what each package's Python imports. The workspace-wide tests
(tests/test_ros_conventions.py, tests/test_architecture.py) check rules on these facts."""
from __future__ import annotations

import ast
import os
import sys
import xml.etree.ElementTree as ET
from typing import Dict, Iterator, Set, Tuple

RUN_TAGS = ("depend", "exec_depend", "run_depend")
INTERFACE_MODULES = ("msg", "srv", "action")


def packages(*srcs: str) -> Dict[str, str]:
    """name -> folder of every package directly under each of `srcs` (the course's src/ and the
    reference solutions' solutions/, say)."""
    found = {}
    for src in srcs:
        for entry in sorted(os.listdir(src)):
            manifest = os.path.join(src, entry, "package.xml")
            if os.path.isfile(manifest):
                found[ET.parse(manifest).getroot().findtext("name")] = os.path.join(src, entry)
    return found


def declared(folder: str) -> Tuple[Set[str], Set[str]]:
    """(run dependencies, every dependency) of a package.xml (format 2)."""
    run, every = set(), set()
    for element in ET.parse(os.path.join(folder, "package.xml")).getroot():
        if element.tag.endswith("depend") and element.text:
            every.add(element.text.strip())
            if element.tag in RUN_TAGS:
                run.add(element.text.strip())
    return run, every


def role(folder: str) -> str:
    """The package's `<export><course_role>` ('' when it has none)."""
    export = ET.parse(os.path.join(folder, "package.xml")).getroot().find("export")
    return ((export.findtext("course_role") if export is not None else None) or "").strip()


def python_modules_of(pkgs: Dict[str, str]) -> Dict[str, str]:
    """importable top-level module -> the package that provides it: each package under its own
    name (its messages), and each package's src/<module>/ (catkin_python_setup)."""
    modules = {name: name for name in pkgs}
    for name, folder in pkgs.items():
        src = os.path.join(folder, "src")
        if os.path.isdir(src):
            for entry in os.listdir(src):
                if os.path.isfile(os.path.join(src, entry, "__init__.py")):
                    modules[entry] = name
    return modules


def python_files(folder: str) -> Iterator[Tuple[str, bool]]:
    """(path, is test code) of every Python file and #!python script of a package; the package's
    own setup.py (a build step) is left out."""
    for root, dirs, files in os.walk(folder):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for name in files:
            path = os.path.join(root, name)
            if name == "setup.py" and root == folder:
                continue
            if not name.endswith(".py"):
                with open(path, "rb") as f:
                    first = f.readline()
                if not (first.startswith(b"#!") and b"python" in first):
                    continue
            yield path, os.path.relpath(path, folder).split(os.sep)[0] == "test"


def imports(path: str) -> Set[str]:
    """Dotted names of the absolute, non-stdlib imports in one file (`a.b` for `from a.b import c`)."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module)
    return {n for n in names if n.split(".")[0] not in sys.stdlib_module_names}
