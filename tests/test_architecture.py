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

The folders outside the packages follow rules of their own, on every Python file they hold:

- tools/ (the demo, the flake hunter, the multi-architecture image build) imports libraries and
  the test support;
- bench/ (the benchmarks) and tests/ (the workspace-wide tests, the end-to-end suites among them)
  measure and test everything: they may import any package's modules but an exercise's;
- no Python file anywhere puts a folder on sys.path: a package is imported as installed (a
  sourced workspace, or the PYTHONPATH a make target sets), and the code it needs from a script
  lives in a package, never in a sibling file reached through sys.path.
"""
from __future__ import annotations

import ast
import os
import re
from pathlib import Path
from typing import Dict, Iterator, List, Set, Tuple

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
# The folders outside the packages -> roles whose Python modules their files may import (besides messages).
FOLDERS: Dict[str, Set[str]] = {
    "tools": {"library", "test_support"},
    "bench": set(ROLES) - {"exercise"},
    "tests": set(ROLES) - {"exercise"},
}
# Never read for the sys.path rule: version control, the venvs, what builds and runs write, node's packages.
NOT_OURS = {".git", ".venv", ".venv-jupyter", ".venv-hub", ".hub", "build", "devel", "install", "logs", "output",
            "grades", "podman-logs", "node_modules", "__pycache__", ".hypothesis"}
SYS_PATH_EDITS = {"insert", "append", "extend", "remove", "pop", "clear"}


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


def python_files_of(folder: str) -> Iterator[str]:
    """Every Python file and #!python script under `folder`."""
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d not in NOT_OURS)
        for name in sorted(files):
            path = os.path.join(root, name)
            if not name.endswith(".py"):
                with open(path, "rb") as f:
                    first = f.readline()
                if not (first.startswith(b"#!") and b"python" in first):
                    continue
            yield path


def folder_violations(root: Path = ROOT, *srcs: str) -> List[str]:
    """The import rules of FOLDERS on every Python file of tools/, bench/ and tests/."""
    role_of = roles(*srcs)
    providers = scan.python_modules_of(scan.packages(*(srcs or (SRC, SOLUTIONS))))
    found = []
    for folder, allowed in sorted(FOLDERS.items()):
        for path in python_files_of(str(root / folder)):
            for dotted in sorted(scan.imports(path)):
                parts = dotted.split(".")
                provider = providers.get(parts[0])
                if provider is None or (len(parts) > 1 and parts[1] in scan.INTERFACE_MODULES):
                    continue
                if role_of.get(provider) not in allowed:
                    found.append("%s (%s/) imports %s from %s (%s)" % (
                        os.path.relpath(path, root), folder, dotted, provider, role_of.get(provider)))
    return found


def is_sys_path(node: ast.AST) -> bool:
    return (isinstance(node, ast.Attribute) and node.attr == "path" and isinstance(node.value, ast.Name)
            and node.value.id == "sys")


def saved_copies(function: ast.AST) -> Set[str]:
    """Names a function binds to a copy of sys.path (`saved = list(sys.path)`), which it may put back."""
    names = set()
    for node in ast.walk(function):
        if isinstance(node, ast.Assign):
            pairs: List[Tuple[ast.AST, ast.AST]] = []
            for target in node.targets:
                if isinstance(target, ast.Tuple) and isinstance(node.value, ast.Tuple):
                    pairs += zip(target.elts, node.value.elts)
                else:
                    pairs.append((target, node.value))
            for target, value in pairs:
                if (isinstance(target, ast.Name) and isinstance(value, ast.Call) and isinstance(value.func, ast.Name)
                        and value.func.id == "list" and len(value.args) == 1 and is_sys_path(value.args[0])):
                    names.add(target.id)
    return names


def sys_path_edits(path: str) -> List[str]:
    """`file:line: statement` for each place a file changes sys.path (or adds a site folder to it).
    A function putting back the copy of it that it saved (after a library it called added to it)
    makes no edit."""
    with open(path, encoding="utf-8") as f:
        source = f.read()
    tree = ast.parse(source, path)
    restores = set()
    for function in ast.walk(tree):
        if isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
            saved = saved_copies(function)
            for node in ast.walk(function):
                if (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Subscript)
                        and is_sys_path(node.targets[0].value) and isinstance(node.value, ast.Name)
                        and node.value.id in saved):
                    restores.add(node)
    found = []
    for node in sorted(ast.walk(tree), key=lambda n: getattr(n, "lineno", 0)):
        edit = False
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            edit = ((node.func.attr in SYS_PATH_EDITS and is_sys_path(node.func.value))
                    or (node.func.attr == "addsitedir" and isinstance(node.func.value, ast.Name)
                        and node.func.value.id == "site"))
        elif isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)) and node not in restores:
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            edit = any(is_sys_path(t) or (isinstance(t, ast.Subscript) and is_sys_path(t.value)) for t in targets)
        if edit:
            found.append("%s:%d: %s" % (path, node.lineno, ast.get_source_segment(source, node)))
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


def test_tools_bench_and_tests_follow_their_rules():
    problems = folder_violations()
    assert not problems, "\n".join(problems)


def test_a_tool_importing_the_grading_code_is_caught(tmp_path):
    """The folder rule must catch the mistake it exists for: a script in tools/ reaching into the grader."""
    make_packages(tmp_path, "cli", (("grader", "grading", ""), ("kit", "test_support", "")))
    (tmp_path / "tools").mkdir()
    (tmp_path / "tools" / "report.py").write_text("from grader_core.cli import main\nfrom kit_core import cli\n")
    assert folder_violations(tmp_path, str(tmp_path / "src")) == [
        "tools/report.py (tools/) imports grader_core.cli from grader (grading)"]


def test_no_python_file_edits_sys_path():
    """Packages are imported as installed, never by a script putting their source folder on sys.path."""
    edits = [edit for path in python_files_of(str(ROOT)) for edit in sys_path_edits(path)]
    assert not edits, "sys.path edited (a package belongs installed, shared code in a package):\n" + "\n".join(
        os.path.relpath(e, ROOT) for e in edits)


def test_each_kind_of_sys_path_edit_is_caught(tmp_path):
    """Six edits (lines 2-7), then a read and a function putting back the copy it saved: no edit."""
    lines = ["import site, sys", "{path}.insert(0, 'src')", "{path}.append('x')", "{path}[:0] = ['y']",
             "{path} += ['z']", "{path} = ['w']", "site.addsitedir('v')", "print({path})", "def generate():",
             "    saved, modules = list({path}), set(sys.modules)", "    try:", "        pass", "    finally:",
             "        {path}[:] = saved", ""]
    script = tmp_path / "bench.py"
    script.write_text("\n".join(lines).format(path="sys.path"))
    assert [e.split(":", 2)[1] for e in sys_path_edits(str(script))] == ["2", "3", "4", "5", "6", "7"]


def test_the_end_to_end_suites_are_marked_and_left_out_of_make_test():
    """Every module of tests/e2e carries pytest's e2e marker, which pytest.ini's addopts deselect
    (make test, make flake-hunt); each suite's make target selects it with -m e2e."""
    addopts = re.search(r"^addopts\s*=(.*)$", (ROOT / "pytest.ini").read_text(), re.MULTILINE).group(1)
    assert '-m "not e2e"' in addopts, addopts
    modules = sorted((ROOT / "tests" / "e2e").glob("test_*.py"))
    assert modules
    unmarked = [m.name for m in modules if not any(
        isinstance(node, ast.Assign) and [getattr(t, "id", "") for t in node.targets] == ["pytestmark"]
        and ast.unparse(node.value) == "pytest.mark.e2e" for node in ast.parse(m.read_text()).body)]
    assert not unmarked, "tests/e2e modules without `pytestmark = pytest.mark.e2e`: %s" % unmarked
    makefile = (ROOT / "Makefile").read_text()
    for module in modules:
        assert "tests/e2e/%s" % module.name in makefile, "no make target runs tests/e2e/%s" % module.name
