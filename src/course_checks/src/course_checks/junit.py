"""Read the JUnit XML rostest leaves behind, and write our own.

rostest (without --text) writes two kinds of files under $ROS_HOME/test_results/<pkg>/:
- `rostest-<test file>.xml`: one testcase per <test> tag; it fails when the check node did not
  run, crashed before reporting, or went past its time-limit;
- `rosunit-<test-name>.xml`: the check node's own unittest results, one testcase per test
  method, whose failure text is the assertion message followed by a traceback.
What a student needs is the assertion message, without the traceback and unittest's prefixes.
"""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from typing import Iterable, List, NamedTuple, Optional, Sequence, Tuple

# unittest's own words before the message a check passed to an assertion (checks turn them off
# with longMessage = False; a check that forgets still reads as its sentence alone).
_UNITTEST_PREFIX = re.compile(r"^(?:.{0,300}? is not (?:true|false)|unexpectedly None|.{0,300}? is not None"
                              r"|.{0,300}? != .{0,300}?) : ", re.DOTALL)
_TRACEBACK = re.compile(r'^\s*(File "|Traceback \(most recent call last\))')
_TIME_LIMIT = re.compile(r"max time \[([\d.]+)s\] allotted for test \[([^\]]*)\]")
_NO_RESULTS = re.compile(r"test \[([^\]]*)\] did not generate test results")
# Error types that are rostest's, not an exception in the check: their message says it all.
_ROSTEST_ERRORS = ("", "AssertionError", "RLTestTimeoutException")
_NOT_EXECUTABLE = re.compile(r"Test node \[([^\]]*)\] does not exist or is not executable")


class Case(NamedTuple):
    """One testcase: `problem` is "failure", "error" or None (passed); `message` is cleaned."""
    name: str
    classname: str
    time: float
    problem: Optional[str]
    message: str


class Suite(NamedTuple):
    tests: int
    cases: Tuple[Case, ...]

    @property
    def failed(self) -> Tuple[Case, ...]:
        return tuple(c for c in self.cases if c.problem)


def clean_message(text: str) -> str:
    """The assertion message a check wrote, from a JUnit failure text: the lines before the
    traceback, without unittest's "None is not true : " kind of prefix; rostest's own failures (time
    limit, no results, missing check node) in plain words."""
    kept = []
    for line in (text or "").strip().splitlines():
        if _TRACEBACK.match(line):
            break
        kept.append(line.rstrip())
    message = "\n".join(kept).strip()
    message = _UNITTEST_PREFIX.sub("", message, count=1)
    limit = _TIME_LIMIT.search(message)
    if limit:
        return "the check [%s] did not finish within its time limit of %s s" % (limit.group(2), limit.group(1))
    none = _NO_RESULTS.search(message)
    if none:
        return "the check [%s] ended without reporting results (it crashed or was killed)" % none.group(1)
    missing = _NOT_EXECUTABLE.search(message)
    if missing:
        return "the check node [%s] does not exist or is not executable" % missing.group(1)
    return message


def _case(element: ET.Element) -> Case:
    problem, message = None, ""
    for kind in ("failure", "error"):
        found = element.find(kind)
        if found is not None:
            problem = kind
            message = clean_message(found.text or found.get("message", "") or found.get("type", ""))
            kind_name = found.get("type", "")
            if kind == "error" and kind_name not in _ROSTEST_ERRORS and not message.startswith(kind_name):
                message = "%s: %s" % (kind_name, message) if message else kind_name
            break
    try:
        elapsed = float(element.get("time", "0") or 0)
    except ValueError:
        elapsed = 0.0
    return Case(element.get("name", "?"), element.get("classname", ""), elapsed, problem, message)


def parse_text(xml_text: str) -> Suite:
    """A JUnit document (<testsuite> or <testsuites>) as one Suite."""
    root = ET.fromstring(xml_text)
    suites = [root] if root.tag == "testsuite" else list(root.iter("testsuite"))
    cases: List[Case] = []
    tests = 0
    for suite in suites:
        found = [_case(e) for e in suite.iter("testcase")]
        cases.extend(found)
        try:
            tests += int(suite.get("tests", len(found)))
        except ValueError:
            tests += len(found)
    return Suite(tests, tuple(cases))


def parse_file(path: str) -> Optional[Suite]:
    """The file's Suite, or None when it is not readable JUnit XML."""
    try:
        with open(path, "rb") as f:
            return parse_text(f.read().decode("utf-8", errors="replace"))
    except (OSError, ET.ParseError):
        return None


def combine(launcher: Optional[Suite], checks: Sequence[Suite]) -> Tuple[int, List[Tuple[str, str]]]:
    """Test count and (name, message) failures of one rostest run, from its rostest-*.xml suite
    (`launcher`) and the check nodes' rosunit-*.xml suites (`checks`). The checks' own test
    methods are what counts; the launcher adds the checks that did not run or report."""
    tests = sum(s.tests for s in checks) if checks else (launcher.tests if launcher else 0)
    failures = [(c.name, c.message) for s in ([launcher] if launcher else []) for c in s.failed]
    failures += [(c.name, c.message) for s in checks for c in s.failed]
    return tests, failures


def write(path: str, suite_name: str, cases: Iterable[Case]) -> None:
    """Write `cases` as one JUnit <testsuite> (what CI tools and catkin_test_results read)."""
    cases = list(cases)
    root = ET.Element("testsuite", name=suite_name, tests=str(len(cases)),
                      failures=str(sum(c.problem == "failure" for c in cases)),
                      errors=str(sum(c.problem == "error" for c in cases)),
                      time="%.3f" % sum(c.time for c in cases))
    for case in cases:
        element = ET.SubElement(root, "testcase", classname=case.classname or suite_name, name=case.name,
                                time="%.3f" % case.time)
        if case.problem:
            first_line = case.message.splitlines()[0] if case.message else case.problem
            ET.SubElement(element, case.problem, message=first_line, type=case.problem).text = case.message
    ET.ElementTree(root).write(path, encoding="utf-8", xml_declaration=True)
