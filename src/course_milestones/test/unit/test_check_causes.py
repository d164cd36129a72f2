"""Every failure of every Python check carries its cause (course_format.causes): read from the
check nodes' source, each `self.fail(msg)`, each `self.assert*(..., msg)` and each `raise` gives a
message that is a causes.Finding where it is made, so a new check, or a new assertion in one, that
fails without a cause fails here. A message counts as a Finding when it is
- a call of causes.finding (or finding),
- a call of a helper known to return one (FINDING_HELPERS), or
- a name (or self./cls. attribute) that every assignment in its module gives a Finding, or the
  Finding a helper returns in a tuple (FINDING_IN_TUPLE: `result, problem = kp.discover_keymap(...)`).
An assertion without a message keeps unittest's words: only a check that names its failures' cause
once (MilestoneCase.failure_cause: the checks of the course's own tools) may have one. A `raise` is
`raise failure(<Finding>)` (milestone_case.failure records the cause), or a bare re-raise.
Every cause key a node or a helper names is in causes.CAUSES.
"""
import ast
import re
import unittest
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Set, Tuple

import pytest

from course_checks import artifacts
from course_format import causes, course_file
from course_milestones import messages, milestone_case, students

NODES = Path(__file__).resolve().parents[2] / "nodes"
COURSES = Path(__file__).resolve().parents[4] / "courses"
# The checks: run_steps (every course's data milestones) and each course's own Python checks,
# the file its checks/NAME.test runs (args="$(dirname)/FILE.py"); the helpers: this library's
# modules and the other modules of a course's checks/ folder (its unit tests aside).
RUN = re.compile(r'args="\$\(dirname\)/([\w.-]+\.py)')
CHECKS = [NODES / "run_steps"] + sorted({t.parent / name for t in COURSES.glob("*/checks/*.test")
                                            for name in RUN.findall(t.read_text())})
HELPERS = sorted(Path(students.__file__).resolve().parent.glob("*.py")) + sorted(
    p for p in COURSES.glob("*/checks/*.py") if p not in CHECKS and not p.name.startswith("test_"))

# Helpers whose result (when it is a failure) is a causes.Finding.
FINDING_HELPERS = {
    "finding",                # causes.finding
    "not_found_message",      # students: no executable of the package did what was asked
    "role_missing",           # students: no started script registered the topic asked for
    "missing_launch_file",    # launch_files: not_started
    "missing_simulators",     # two_sims: wrong_launch
    "failure_message",        # keymap: not_moving, node_exited, exited_early
    "run_steps",              # steps.run: the failing step's Finding (run_steps)
}
# Helpers returning a tuple whose element at that index is a Finding (or None).
FINDING_IN_TUPLE = {"discover_keymap": 1}
# Where each assertion method takes its message, by position.
MSG_POSITION = dict.fromkeys(("assertTrue", "assertFalse", "assertIsNone", "assertIsNotNone"), 1)
MSG_POSITION.update(dict.fromkeys(("assertEqual", "assertNotEqual", "assertIn", "assertNotIn", "assertIs",
                                   "assertIsNot", "assertIsInstance", "assertNotIsInstance", "assertLess",
                                   "assertLessEqual", "assertGreater", "assertGreaterEqual", "assertCountEqual",
                                   "assertRegex", "assertNotRegex", "assertListEqual", "assertDictEqual"), 2))
MSG_POSITION.update(dict.fromkeys(("assertAlmostEqual", "assertNotAlmostEqual"), 3))
MSG_POSITION["fail"] = 0


def _called(node: ast.AST) -> str:
    """The name a call calls: f(...) -> f, a.b.f(...) -> f."""
    if isinstance(node, ast.Call):
        func = node.func
        return func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
    return ""


def _target_name(node: ast.AST) -> str:
    """x -> x, self.x / cls.x -> x (an attribute of the test case)."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"):
        return node.attr
    return ""


class Module:
    """One check node's source, read for its failures."""

    def __init__(self, source: str, name: str = "<source>") -> None:
        self.name = name
        self.tree = ast.parse(source)
        self.assigned: Dict[str, List[Tuple[ast.AST, Optional[int]]]] = {}  # name -> (value, index in a tuple)
        for node in ast.walk(self.tree):
            if isinstance(node, ast.Assign):
                for target in node.targets:
                    if isinstance(target, ast.Tuple):
                        for i, element in enumerate(target.elts):
                            if _target_name(element):
                                self.assigned.setdefault(_target_name(element), []).append((node.value, i))
                    elif _target_name(target):
                        self.assigned.setdefault(_target_name(target), []).append((node.value, None))

    def is_finding(self, expr: ast.AST, seen: Optional[Set[str]] = None) -> bool:
        seen = set() if seen is None else seen
        if _called(expr) in FINDING_HELPERS:
            return True
        if isinstance(expr, ast.BoolOp) and isinstance(expr.op, ast.Or):
            return all(self.is_finding(v, seen) for v in expr.values)
        name = _target_name(expr)
        if name and name not in seen and self.assigned.get(name):
            seen.add(name)
            return all(self._gives_finding(value, index, seen) for value, index in self.assigned[name])
        return False

    def _gives_finding(self, value: ast.AST, index: Optional[int], seen: Set[str]) -> bool:
        if index is not None:
            return FINDING_IN_TUPLE.get(_called(value)) == index
        if isinstance(value, ast.Constant) and value.value in ("", None):  # no problem (yet)
            return True
        return self.is_finding(value, seen)

    def failure_cause(self) -> str:
        """The failure_cause a test case class of this module sets, or ''."""
        for node in ast.walk(self.tree):
            if isinstance(node, ast.Assign) and any(_target_name(t) == "failure_cause" for t in node.targets):
                if isinstance(node.value, ast.Constant):
                    return node.value.value
        return ""

    def failures(self) -> Iterator[Tuple[int, str, Optional[ast.AST]]]:
        """(line, what, message) of every self.fail / self.assert* call; message None when none given."""
        for node in ast.walk(self.tree):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and isinstance(node.func.value, ast.Name) and node.func.value.id == "self"
                    and node.func.attr in MSG_POSITION):
                continue
            position = MSG_POSITION[node.func.attr]
            keyword = next((k.value for k in node.keywords if k.arg == "msg"), None)
            message = node.args[position] if len(node.args) > position else keyword
            yield node.lineno, node.func.attr, message

    def raises(self) -> Iterator[Tuple[int, Optional[ast.AST]]]:
        for node in ast.walk(self.tree):
            if isinstance(node, ast.Raise):
                yield node.lineno, node.exc

    def uncaused(self) -> List[str]:
        """Where this module fails without a cause, as 'line N: what'."""
        found = []
        default = self.failure_cause()
        for line, what, message in self.failures():
            if message is None:
                if not default and what != "fail":
                    found.append("line %d: %s without a message (and no failure_cause)" % (line, what))
                elif what == "fail" and not default:
                    found.append("line %d: fail() without a message" % line)
            elif not self.is_finding(message):
                found.append("line %d: %s(..., %s)" % (line, what, ast.unparse(message)[:80]))
        for line, exc in self.raises():
            if exc is None:
                continue  # a re-raise
            if not (_called(exc) == "failure" and exc.args and self.is_finding(exc.args[0])):
                found.append("line %d: raise %s" % (line, ast.unparse(exc)[:80]))
        return found


def _keys_named(tree: ast.AST) -> List[Tuple[int, str]]:
    """The literal cause keys of causes.finding calls, of `default`s given to causes.of and of failure_cause."""
    keys = []
    for node in ast.walk(tree):
        if _called(node) == "finding" and node.args and isinstance(node.args[0], ast.Constant):
            keys.append((node.lineno, node.args[0].value))
        if _called(node) == "of" and len(node.args) > 1 and isinstance(node.args[1], ast.Constant):
            keys.append((node.lineno, node.args[1].value))
        if isinstance(node, ast.Assign) and any(_target_name(t) in ("failure_cause", "cause") for t in node.targets) \
                and isinstance(node.value, ast.Constant) and node.value.value:
            keys.append((node.lineno, node.value.value))
        if isinstance(node, ast.IfExp):
            for branch in (node.body, node.orelse):
                if isinstance(branch, ast.Constant) and isinstance(branch.value, str) and branch.value in causes.BY_KEY:
                    keys.append((node.lineno, branch.value))
    return keys


def test_there_are_checks():
    """A file per Python check of the built-in course, and run_steps for its data milestones."""
    python_checks = [m for m in course_file.load(course_file.builtin_course_dir()).milestones if m.test_file]
    ours = [p for p in CHECKS if p.parent == Path(course_file.builtin_course_dir()) / "checks"]
    assert len(ours) == len(python_checks) >= 14 and all(p.is_file() for p in CHECKS), [p.name for p in CHECKS]


@pytest.mark.parametrize("path", CHECKS, ids=lambda p: p.name)
def test_every_failure_of_a_check_carries_its_cause(path):
    module = Module(path.read_text(), path.name)
    assert not module.uncaused(), "%s fails without a cause (wrap the message in causes.finding(KEY, ...)):\n%s" % (
        path.name, "\n".join(module.uncaused()))


@pytest.mark.parametrize("path", CHECKS + HELPERS, ids=lambda p: p.name)
def test_the_keys_named_are_causes(path):
    unknown = [(line, key) for line, key in _keys_named(ast.parse(path.read_text())) if key not in causes.BY_KEY]
    assert not unknown, "%s names cause keys that are not in causes.CAUSES: %s" % (path.name, unknown)


def test_a_failure_without_a_cause_is_found():
    source = '''
class C(MilestoneCase):
    def setUp(self):
        self.problem = lf.missing_launch_file(pkg, "a.launch") or two_sims.missing_simulators({})
        self.other = "no turtlesim"

    def test(self):
        self.assertFalse(self.problem, self.problem)
        result, problem = kp.discover_keymap(k, c, "who")
        self.fail(problem)
        self.assertTrue(x, causes.finding("silent", "%s publishes nothing" % name))
        self.assertTrue(x, "%s publishes nothing" % name)
        self.assertEqual(a, b, "not %s" % b)
        self.assertEqual(a, b)
        self.assertAlmostEqual(a, b, 2, msg="off")
        self.assertTrue(x, self.other)
        self.fail(students.not_found_message(pkg, "publishes /x", tried))
        raise AssertionError("no executable")
        raise failure(causes.finding("not_started", "no executable"))
'''
    found = Module(source).uncaused()
    assert [f.split(":")[0] for f in found] == ["line 12", "line 13", "line 14", "line 15", "line 16",
                                                "line 18"], found


def test_a_check_of_the_course_tools_may_keep_unittest_words():
    source = '''
class C(MilestoneCase):
    failure_cause = "course_tools"

    def test(self):
        self.assertEqual(a, b)
        self.assertTrue(x, "a sentence")
'''
    assert [f.split(":")[0] for f in Module(source).uncaused()] == ["line 7"], Module(source).uncaused()


# The helpers the checks fail with give Findings (what the source rule above takes on trust).

def test_interface_errors_name_their_cause():
    assert messages.InterfaceError("x").cause == "not_generated"
    assert messages.NotBuilt("x").cause == "not_generated"
    assert messages.NoService("x").cause == "no_service"


@pytest.mark.parametrize("output,key", [
    ("NameError: name 'raw_input' is not defined", "python2"),
    ("import: not found", "no_shebang"),
    ("all fine", "not_started"),
])
def test_start_cause_reads_what_the_scripts_printed(output, key):
    assert students.start_cause("", [output]) == key


# What a failing check records (milestone_case), read back as the grader reads it.

class _Check(milestone_case.MilestoneCase):
    __test__ = False  # run by the tests below, not collected

    def test_finding(self):
        self.assertTrue(False, causes.finding("silent", "x publishes nothing on /y"))

    def test_plain(self):
        self.assertEqual(1, 2)


class _ToolsCheck(_Check):
    failure_cause = "course_tools"


@pytest.mark.parametrize("case,test,recorded", [
    (_Check, "test_finding", ["silent"]),
    (_Check, "test_plain", []),
    (_ToolsCheck, "test_finding", ["silent"]),
    (_ToolsCheck, "test_plain", ["course_tools"]),
])
def test_a_failing_check_records_its_cause(tmp_path, monkeypatch, case, test, recorded):
    monkeypatch.setenv(artifacts.ENV_VAR, str(tmp_path))
    result = unittest.TestResult()
    case(test).run(result)
    assert len(result.failures) == 1
    assert set(causes.recorded(str(tmp_path))) == set(recorded)


def test_a_failure_raised_outside_a_test_records_its_cause(tmp_path, monkeypatch):
    monkeypatch.setenv(artifacts.ENV_VAR, str(tmp_path))
    error = milestone_case.failure(causes.finding("not_started", "no executable my_node.py"))
    assert isinstance(error, AssertionError) and str(error) == "no executable my_node.py"
    assert causes.recorded(str(tmp_path)) == ["not_started"]
