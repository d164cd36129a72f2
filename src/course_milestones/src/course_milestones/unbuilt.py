"""What a student's package holds but its build did not make, said in words a student can act on.

A .msg, .srv or .action file is only usable once catkin_make generated its code: that takes
add_message_files()/add_service_files()/add_action_files() naming it and a generate_messages()
call in the package's CMakeLists.txt. A Python module in `src/<module>/` is only importable by the
package's nodes once catkin_python_setup() (and a setup.py) installed it in the devel space.
Judged by path in the devel space that built the package: a module of the same name elsewhere
(another workspace) never counts. One detector for the checks (a student running `rostest` with
their own overlay sourced sees the same sentences) and the grader. Pure file reading.
"""
from __future__ import annotations

import glob
import os
import re
from typing import List

from course_format import causes
from course_milestones.scripts import SKIPPED_DIRS

_FUNCTIONS = {"msg": "add_message_files", "srv": "add_service_files", "action": "add_action_files"}
_COMMENT = re.compile(r"#[^\n]*")


def _cmake_text(package_dir: str) -> str:
    try:
        with open(os.path.join(package_dir, "CMakeLists.txt"), errors="replace") as f:
            return _COMMENT.sub("", f.read(1024 * 1024))
    except OSError:
        return ""


def _regular_file(path: str) -> bool:
    """A regular file, its links not followed (the devel space is the student's)."""
    try:
        return os.path.isfile(path) and not os.path.islink(path)
    except OSError:
        return False


def _catkin_shim(path: str) -> bool:
    """Whether `path` is the __init__.py catkin_python_setup() puts in the devel space (it extends
    the module's path to the package's src/; generate_messages() alone writes an empty one)."""
    if not _regular_file(path):
        return False
    try:
        with open(path, "rb") as f:
            return b"__extended_path" in f.read(64 * 1024)
    except OSError:
        return False


def _definitions(package_dir: str, kind: str) -> List[str]:
    folder = os.path.join(package_dir, kind)
    try:
        names = sorted(os.listdir(folder)) if os.path.isdir(folder) and not os.path.islink(folder) else []
    except OSError:
        return []
    return [n[:-len(kind) - 1] for n in names if n.endswith("." + kind) and re.match(r"^[A-Za-z]\w*\.", n)]


def _advice(pkg: str, kind: str, base: str, cmake: str) -> str:
    function = _FUNCTIONS[kind]
    steps = []
    listed = re.search(r"%s\s*\(([^)]*)\)" % function, cmake)
    if listed is None or not re.search(r"\b%s\.%s\b" % (re.escape(base), kind), listed.group(1)):
        steps.append("add %s.%s to %s()" % (base, kind, function))
    if not re.search(r"\bgenerate_messages\s*\(", cmake):
        steps.append("call generate_messages()")
    if not re.search(r"\bmessage_generation\b", cmake):
        steps.append("find_package(catkin REQUIRED COMPONENTS message_generation ...)")
    if not steps:
        return "%s's CMakeLists.txt names it, yet catkin_make did not generate it (see the build's output)" % pkg
    return "in %s's CMakeLists.txt, %s" % (pkg, "; ".join(steps))


def problems(package_dir: str, pkg: str, devel: str) -> List[str]:
    """One sentence per definition file of `pkg` (its source folder `package_dir`) without its
    generated Python in the devel space `devel` that built it, and per Python module in
    `src/<module>/` that space does not provide."""
    found: List[str] = []
    cmake = _cmake_text(package_dir)
    sites = glob.glob(os.path.join(devel, "lib", "python3*", "*-packages"))

    def generated(kind: str, module: str) -> bool:
        return any(_regular_file(os.path.join(site, pkg, kind, "_%s.py" % module)) for site in sites)
    for kind in ("msg", "srv", "action"):
        for base in _definitions(package_dir, kind):
            module, folder = (base + "Action", "msg") if kind == "action" else (base, kind)
            if not generated(folder, module):
                found.append(causes.finding(
                    "messages_not_built", "%s/%s is not built (%s/%s/%s.%s has no generated code): %s"
                    % (pkg, base, pkg, kind, base, kind, _advice(pkg, kind, base, cmake))))
    src = os.path.join(package_dir, "src")
    for module in sorted(os.listdir(src)) if os.path.isdir(src) and not os.path.islink(src) else []:
        if module in SKIPPED_DIRS or not _regular_file(os.path.join(src, module, "__init__.py")):
            continue
        if not any(_catkin_shim(os.path.join(site, module, "__init__.py")) for site in sites):
            found.append(causes.finding(
                "module_not_built", "%s/src/%s is a Python module but is not built, so the package's nodes cannot "
                "import it: "
                         "add a setup.py naming it and call catkin_python_setup() in %s's CMakeLists.txt"
                         % (pkg, module, pkg)))
    return found
