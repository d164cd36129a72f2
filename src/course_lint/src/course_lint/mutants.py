"""Mutants of a reference package: the reference with one mistake a student could make.

A check that passes a mutant cannot tell that mistake from a right answer; `course-lint` grades
every mutant to show which mistakes each milestone's check catches. The operators here are
ROS-specific (a topic renamed, the node exiting after one message, a message left out of the
build, ...) and work on the text of the package's files: Python nodes (with `ast`, see
python_sites), C++ sources, CMakeLists.txt and launch files (see text_sites). Pure: no ROS.
"""
from __future__ import annotations

import ast
import os
from typing import AbstractSet, Callable, Dict, List, NamedTuple, Optional, Sequence, Tuple

from course_lint import python_sites as py
from course_lint import text_sites as tx
from course_lint import used_files

PYTHON, CPP, CMAKE, LAUNCH = "python", "cpp", "cmake", "launch"
CPP_SUFFIXES = (".cpp", ".cc", ".cxx", ".h", ".hpp")
LAUNCH_SUFFIXES = (".launch", ".launch.xml")
# Folders of a package that hold no code a milestone runs: tests, build outputs, VCS.
SKIPPED_DIRS = frozenset({"test", "tests", "build", "devel", "install", "__pycache__", ".git"})
# Mutants per operator per package at the most: each is one build and one milestone run.
CAP = 3
MAX_FILE_BYTES = 512 * 1024

Sites = Callable[[str], List[str]]


class Operator(NamedTuple):
    name: str
    description: str
    sites: Dict[str, Sites]  # file kind -> the file's mutated texts, one per site


class Mutant(NamedTuple):
    package: str  # the package's folder name
    operator: Operator
    path: str  # the mutated file, relative to the package's folder
    line: int  # the first line that differs
    changed: str  # that line as mutated, stripped
    text: str  # the file's whole mutated text


OPERATORS: Tuple[Operator, ...] = (
    Operator("topic_renamed", "a topic, service or action name renamed; in a launch file, a remap's target",
             {PYTHON: py.topic_renamed, CPP: tx.cpp_topic_renamed, LAUNCH: tx.remap_renamed}),
    Operator("type_changed", "a publisher's or subscriber's message type changed to std_msgs Empty or String",
             {PYTHON: py.type_changed}),
    Operator("exit_after_one", "the node exits right after its first message from this publish",
             {PYTHON: py.exit_after_one, CPP: tx.cpp_exit_after_one}),
    Operator("publish_removed", "a publish call left out", {PYTHON: py.publish_removed, CPP: tx.cpp_publish_removed}),
    Operator("no_spin", "no spin: the node's main thread ends instead of waiting for callbacks",
             {PYTHON: py.no_spin, CPP: tx.cpp_no_spin}),
    Operator("rate_div10", "a loop rate divided by ten", {PYTHON: py.rate_div10, CPP: tx.cpp_rate_div10}),
    Operator("swap_xy", "x and y swapped on one line", {PYTHON: py.swap_xy, CPP: tx.cpp_swap_xy}),
    Operator("pen_off", "the pen colour off: r, g, b each 255 minus itself", {PYTHON: py.pen_off}),
    Operator("param_ignored", "a parameter ignored: get_param's default used instead", {PYTHON: py.param_ignored}),
    Operator("param_changed", "a launch file's <param> value changed", {LAUNCH: tx.param_changed}),
    Operator("node_left_out", "a launch file's <node> left out", {LAUNCH: tx.node_left_out}),
    Operator("service_wrong", "a service answers wrong: its response's values left empty", {PYTHON: py.service_wrong}),
    Operator("msg_left_out", "a message, service or action file left out of the build",
             {CMAKE: tx.msg_left_out}),
)


def by_names(names: Sequence[str]) -> Tuple[Operator, ...]:
    """The operators named, in the table's order; ValueError naming any unknown one."""
    known = {op.name for op in OPERATORS}
    unknown = sorted(set(names) - known)
    if unknown:
        raise ValueError("unknown operator(s): %s (known: %s)" % (", ".join(unknown), ", ".join(sorted(known))))
    return tuple(op for op in OPERATORS if op.name in names)


def kind_of(path: str, text: str) -> Optional[str]:
    """Which operators' sites a file has: by its name, or a python shebang for a script."""
    name = os.path.basename(path)
    if name == "CMakeLists.txt":
        return CMAKE
    if name.endswith(CPP_SUFFIXES):
        return CPP
    if name.endswith(LAUNCH_SUFFIXES):
        return LAUNCH
    if name == "setup.py":
        return None
    if name.endswith(".py") or (text.startswith("#!") and "python" in text.split("\n", 1)[0]):
        return PYTHON
    return None


def package_files(folder: str) -> List[Tuple[str, str, str]]:
    """(path relative to folder, kind, text) of every file an operator applies to, sorted."""
    found = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("."))
        for name in sorted(files):
            path = os.path.join(root, name)
            if os.path.islink(path) or os.path.getsize(path) > MAX_FILE_BYTES:
                continue
            try:
                with open(path, encoding="utf-8") as f:
                    text = f.read()
            except (OSError, UnicodeDecodeError):
                continue
            kind = kind_of(name, text)
            if kind:
                found.append((os.path.relpath(path, folder), kind, text))
    return found


def first_change(original: str, mutated: str) -> Tuple[int, str]:
    """The first line (1-based) where the texts differ, and that line as mutated."""
    old, new = original.splitlines(), mutated.splitlines()
    for number, (a, b) in enumerate(zip(old, new), 1):
        if a != b:
            return number, b.strip()
    number = min(len(old), len(new)) + 1
    return number, (new[number - 1].strip() if number <= len(new) else "")


def spread(items: List, cap: int) -> List:
    """At most `cap` of the items, spread over the list (first and last kept)."""
    if len(items) <= cap:
        return items
    if cap == 1:
        return items[:1]
    return [items[round(i * (len(items) - 1) / (cap - 1))] for i in range(cap)]


def mutated_texts(operator: Operator, kind: str, text: str) -> List[str]:
    """The operator's mutated texts of one file: changed, distinct, Python still parsing."""
    sites = operator.sites.get(kind)
    if sites is None:
        return []
    found: List[str] = []
    for new in sites(text):
        if new != text and new not in found and (kind != PYTHON or parses(new)):
            found.append(new)
    return found


def parses(text: str) -> bool:
    try:
        ast.parse(text)
        return True
    except (SyntaxError, ValueError):
        return False


def package_mutants(folder: str, operators: Sequence[Operator] = OPERATORS, cap: int = CAP,
                    names: AbstractSet[str] = frozenset(), package: str = "") -> Tuple[List[Mutant], List[str]]:
    """Every operator's mutants of the package in `folder` (at most `cap` each), and notes on
    files passed over (Python that does not parse). With `names` (what a milestone's steps start,
    see used_files), only the files they reach, when they reach any, are mutated."""
    files = package_files(folder)
    reached = used_files.used(files, set(names), package or os.path.basename(folder)) if names else None
    files = [f for f in files if reached is None or f[0] in reached]
    notes = ["%s: not Python that parses: no Python mutants" % os.path.join(os.path.basename(folder), path)
             for path, kind, text in files if kind == PYTHON and not parses(text)]
    package = os.path.basename(os.path.normpath(folder))
    found = []
    for operator in operators:
        mine = []
        for path, kind, text in files:
            for new in mutated_texts(operator, kind, text):
                line, changed = first_change(text, new)
                mine.append(Mutant(package, operator, path, line, changed, new))
        found += spread(mine, cap)
    return found, notes
