"""The house rules of docs/architecture.md, checked on the code.

Every package states its role in its package.xml (`<export><course_role>ROLE</course_role>`).
What a package's Python may import from another package of this workspace depends on both roles:

- an exercise (a course text's package) never imports another exercise, a simulator's internals,
  a tool or the grading code; it may import a library, and any package's messages, services and
  actions (`pkg.msg`, `pkg.srv`), which are the interface that travels over ROS anyway;
- a simulator imports only libraries, other simulator packages and messages;
- a library imports only libraries and messages;
- a tool imports libraries and messages; the test support imports libraries and messages;
- test code (a package's `test/` folder) may also import the test support, and a simulator's
  modules, to check a client against the simulator's own numbers;
- the grading code (milestones, grader) may import anything but the test support: it checks
  everyone, and what it needs at run time is a library (course_checks), so that no test framework
  (pytest, selenium, hypothesis) is on the grader's run path.

Talking over ROS (a launch file starting another package's node) is not an import and is free.
"""
from __future__ import annotations

import os
from pathlib import Path
from typing import Dict, List, Set

from course_testkit import package_scan as scan

ROOT = Path(__file__).resolve().parents[1]
SRC = str(ROOT / "src")
SOLUTIONS = str(ROOT / "courses" / "robotics_labs" / "solution")  # the built-in course's reference: the exercises, apart from the course
ARCHITECTURE_DOC = ROOT / "docs" / "architecture.md"
ROLES = ("exercise", "simulator", "library", "tool", "test_support", "grading")
# importer's role -> roles whose Python modules it may import (besides messages, and itself).
MAY_IMPORT: Dict[str, Set[str]] = {
    "exercise": {"library"},
    "simulator": {"library", "simulator"},
    "library": {"library"},
    "tool": {"library"},
    "test_support": {"library"},
    "grading": set(ROLES) - {"test_support"},
}
# What only tests may need: never a run dependency of grading, however indirect.
TEST_FRAMEWORKS = {"python3-pytest", "python3-selenium", "python3-hypothesis"}


def roles(*srcs: str) -> Dict[str, str]:
    return {name: scan.role(folder) for name, folder in scan.packages(*(srcs or (SRC, SOLUTIONS))).items()}


def violations(*srcs: str) -> List[str]:
    srcs = srcs or (SRC, SOLUTIONS)
    pkgs = scan.packages(*srcs)
    role_of = roles(*srcs)
    providers = scan.python_modules_of(pkgs)
    found = []
    for name, folder in pkgs.items():
        role = role_of[name]
        for path, is_test in scan.python_files(folder):
            for dotted in sorted(scan.imports(path)):
                parts = dotted.split(".")
                provider = providers.get(parts[0])
                if provider is None or provider == name:
                    continue
                if len(parts) > 1 and parts[1] in scan.INTERFACE_MODULES:
                    continue
                allowed = MAY_IMPORT.get(role, set()) | ({"test_support", "simulator"} if is_test else set())
                if role_of.get(provider) not in allowed:
                    found.append("%s (%s) imports %s from %s (%s)" % (
                        os.path.relpath(path, os.path.dirname(folder)), role, dotted, provider,
                        role_of.get(provider)))
    return found


def test_every_package_declares_its_role():
    wrong = {name: role for name, role in roles().items() if role not in ROLES}
    assert not wrong, "packages without a known <course_role> (one of %s): %s" % (", ".join(ROLES), wrong)


def test_imports_follow_the_roles():
    problems = violations()
    assert not problems, "\n".join(problems)


def make_packages(tmp_path: Path, module: str, specs) -> None:
    """Packages under tmp_path/src, each (name, role, code of its module <name>_core.<module>)."""
    for name, role, code in specs:
        pkg = tmp_path / "src" / name
        (pkg / "src" / (name + "_core")).mkdir(parents=True)
        (pkg / "src" / (name + "_core") / "__init__.py").write_text("")
        (pkg / "src" / (name + "_core") / (module + ".py")).write_text(code)
        (pkg / "package.xml").write_text('<package format="2"><name>%s</name><export><course_role>%s'
                                         '</course_role></export></package>' % (name, role))


def test_no_exercise_imports_another_exercise(tmp_path):
    """The rule above must catch the mistake it exists for: lab2 importing mybot_teleop's code."""
    make_packages(tmp_path, "keys", (("ex_a", "exercise", "from ex_b_core.keys import Decoder\n"),
                                     ("ex_b", "exercise", "")))
    assert violations(str(tmp_path / "src")) == ["ex_a/src/ex_a_core/keys.py (exercise) imports ex_b_core.keys from ex_b (exercise)"]


def run_path(name: str, pkgs: Dict[str, str]) -> Dict[str, str]:
    """Every run dependency reachable from package `name` (key -> the package that declares it)."""
    reached, todo = {}, [name]
    while todo:
        current = todo.pop()
        for dep in sorted(scan.declared(pkgs[current])[0]):
            if dep not in reached:
                reached[dep] = current
                if dep in pkgs:
                    todo.append(dep)
    return reached


def test_grading_runs_without_test_support_or_test_frameworks():
    pkgs = scan.packages(SRC)
    role_of = roles(SRC)
    for grading in sorted(n for n, r in role_of.items() if r == "grading"):
        reached = run_path(grading, pkgs)
        wrong = sorted("%s (declared by %s)" % (dep, by) for dep, by in reached.items()
                       if dep in TEST_FRAMEWORKS or role_of.get(dep) == "test_support")
        assert not wrong, "%s's run path holds what only tests need: %s" % (grading, ", ".join(wrong))


def test_grading_importing_the_test_support_is_caught(tmp_path):
    """The rule must catch the mistake it exists for: a check node importing course_testkit."""
    make_packages(tmp_path, "main", (("grader", "grading", "from kit_core.browser import chromium\n"),
                                     ("kit", "test_support", "")))
    assert violations(str(tmp_path / "src")) == [
        "grader/src/grader_core/main.py (grading) imports kit_core.browser from kit (test_support)"]


def test_exercises_are_the_solutions_folder_and_nothing_else():
    """The course (src/) holds infrastructure only; every exercise (a reference solution) is in
    courses/robotics_labs/solution/, which holds nothing else: a student's package is never completed by ours."""
    course, solutions = roles(SRC), roles(SOLUTIONS)
    assert sorted(n for n, r in course.items() if r == "exercise") == []
    assert solutions and sorted(n for n, r in solutions.items() if r != "exercise") == []


def test_the_architecture_doc_names_every_package():
    doc = ARCHITECTURE_DOC.read_text(encoding="utf-8")
    missing = sorted(name for name in roles() if "`%s`" % name not in doc)
    assert not missing, "docs/architecture.md does not name: %s" % ", ".join(missing)
