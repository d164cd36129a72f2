"""Which of a package's files a data milestone runs, from the names its steps give.

A package may serve several milestones (the ROS wiki's beginner_tutorials serves five): a mutant
of a file that a milestone never starts survives it and says nothing of its check. A data
milestone's steps name what they start (`rosrun: PKG talker.py`, `roslaunch: PKG x.launch`), so
its mutants can be made of those files only: a script by its name, a C++ executable by the
sources CMakeLists.txt builds it from, a launch file and the package's nodes it starts; and
CMakeLists.txt itself, which builds them all. Pure: no ROS.
"""
from __future__ import annotations

import os
import re
from typing import Dict, Iterable, List, Optional, Set, Tuple

ADD_EXECUTABLE = re.compile(r"\badd_executable\s*\(([^)]*)\)", re.IGNORECASE)
EXECUTABLE_OPTIONS = frozenset({"WIN32", "MACOSX_BUNDLE", "EXCLUDE_FROM_ALL", "IMPORTED", "ALIAS"})
NODE_TAG = re.compile(r"<node\b[^>]*>")
ATTRIBUTE = re.compile(r"""\b(pkg|type)\s*=\s*(["'])(.*?)\2""")
CMAKE = "CMakeLists.txt"

PackageFile = Tuple[str, str, str]  # (path relative to the package, kind, text)


def executables(cmake: str) -> Dict[str, List[str]]:
    """add_executable(NAME [options] SOURCES...) -> {NAME: SOURCES}, paths as written."""
    found = {}
    for call in ADD_EXECUTABLE.finditer(cmake):
        words = [w for w in call.group(1).split() if w.upper() not in EXECUTABLE_OPTIONS]
        if words:
            found[words[0]] = [os.path.normpath(w) for w in words[1:] if "$" not in w]
    return found


def launched(launch: str, package: str) -> Set[str]:
    """The node types of `package` that a launch file starts."""
    types = set()
    for tag in NODE_TAG.finditer(launch):
        attrs = {m.group(1): m.group(3) for m in ATTRIBUTE.finditer(tag.group())}
        if attrs.get("pkg") == package and attrs.get("type"):
            types.add(attrs["type"])
    return types


def used(files: Iterable[PackageFile], names: Set[str], package: str) -> Optional[Set[str]]:
    """The paths of the files the names reach (CMakeLists.txt with them), or None when the names
    reach none: then the milestone may run any of them (a Python check finds its own)."""
    files = list(files)
    built = {}
    for path, _, text in files:
        if os.path.basename(path) == CMAKE:
            built.update(executables(text))
    reached: Set[str] = set()
    todo = set(names)
    while todo:
        name = todo.pop()
        for path, _, text in files:
            if path in reached:
                continue
            if os.path.basename(path) == name or path in built.get(name, ()):
                reached.add(path)
                if path.endswith(".launch") or path.endswith(".launch.xml"):
                    todo |= launched(text, package) - names
    if not reached:
        return None
    return reached | {path for path, _, _ in files if os.path.basename(path) == CMAKE}
