"""How @guard.judged turns the trust guard's violations into a milestone's verdict (no master: a
stand-in guard answers the audit). The guard's hooks in rospy are tested against a real master
by test/trust_guard.test."""
from __future__ import annotations

import unittest
from typing import Dict, List

import pytest

from course_milestones import guard

FAKE = "your node /fake_pose publishes /turtle1/pose, which only turtlesim may publish"


class StandInGuard:
    """What @judged asks of a guard: audit() and the sentences already reported."""

    def __init__(self, violations: List[str]) -> None:
        self.violations = violations
        self.reported: List[str] = []
        self.audits = 0

    def audit(self) -> List[str]:
        self.audits += 1
        return list(self.violations)


@pytest.fixture
def stand_in(monkeypatch):
    def make(violations: List[str]) -> StandInGuard:
        fake = StandInGuard(violations)
        monkeypatch.setattr(guard, "_active", fake)
        return fake
    return make


def outcomes(case: type) -> Dict[str, str]:
    """Run a TestCase class: test name -> 'ok', 'skip' or the last line of its failure/error."""
    result = unittest.TestResult()
    unittest.defaultTestLoader.loadTestsFromTestCase(case).run(result)
    found = {}
    for test, text in result.failures + result.errors:
        found[test.id().rsplit(".", 1)[-1] if "." in test.id() else test.id()] = text.strip().splitlines()[-1]
    for test, _ in result.skipped:
        found[test.id().rsplit(".", 1)[-1]] = "skip"
    return found


def make_case() -> type:
    @guard.judged
    class Case(unittest.TestCase):
        def test_passes(self):
            pass

        def test_fails(self):
            self.fail("the pen did not turn red")

        def test_errors(self):
            raise KeyError("x")

        def test_skipped(self):
            raise unittest.SkipTest("not here")
    return Case


def test_without_violations_the_checks_own_verdicts_stand(stand_in):
    fake = stand_in([])
    assert outcomes(make_case()) == {"test_fails": "AssertionError: the pen did not turn red",
                                     "test_errors": "KeyError: 'x'", "test_skipped": "skip"}
    assert fake.audits == 3, "a skipped test is not judged"


def test_with_a_violation_every_test_fails_with_it_first(stand_in):
    stand_in([FAKE])
    found = outcomes(make_case())
    assert found["test_passes"] == "AssertionError: " + FAKE
    assert found["test_fails"] == "AssertionError: %s (besides, the check saw: the pen did not turn red)" % FAKE
    assert found["test_errors"] == "AssertionError: %s (besides, the check saw: 'x')" % FAKE
    assert found["test_skipped"] == "skip"


def test_several_violations_are_all_named_in_order(stand_in):
    second = "your node /fake offers the service /clear, which only turtlesim may offer"
    stand_in([FAKE, second])
    assert outcomes(make_case())["test_passes"] == "AssertionError: %s; %s" % (FAKE, second)


def test_a_failing_set_up_class_gives_way_to_the_violation(stand_in):
    stand_in([FAKE])

    @guard.judged
    class Case(unittest.TestCase):
        @classmethod
        def setUpClass(cls):
            raise AssertionError("no executable subscribes /turtle1/pose")

        def test_never_runs(self):
            pass
    found = outcomes(Case)
    assert list(found.values()) == ["AssertionError: %s (besides, the check saw: no executable subscribes "
                                    "/turtle1/pose)" % FAKE]


def test_tear_down_reports_only_what_no_test_reported(stand_in):
    fake = stand_in([])
    snapshot = "your node /fake_snapshot offers the service /turtlesim/snapshot, which only turtlesim may offer"

    @guard.judged
    class Case(unittest.TestCase):
        def test_a_passes(self):
            pass

        def test_b_passes(self):
            pass

        def tearDown(self):
            if snapshot not in fake.violations:  # found while saving the canvas, after the first verdict
                fake.violations.append(snapshot)
    result = unittest.TestResult()
    unittest.defaultTestLoader.loadTestsFromTestCase(Case).run(result)
    reported = [(test.id().rsplit(".", 1)[-1], text.strip().splitlines()[-1]) for test, text in result.failures]
    assert reported == [("test_a_passes", "AssertionError: " + snapshot),   # from the first tearDown
                        ("test_b_passes", "AssertionError: " + snapshot)]   # the second test's own verdict
    assert result.errors == [] and fake.reported == [snapshot]


def test_without_a_guard_nothing_changes(monkeypatch):
    monkeypatch.setattr(guard, "_active", None)
    found = outcomes(make_case())
    assert found["test_fails"] == "AssertionError: the pen did not turn red" and "test_passes" not in found


def test_failure_text():
    assert guard.failure_text([FAKE], None) == FAKE
    assert guard.failure_text([FAKE], AssertionError("first line\nsecond")) == \
        FAKE + " (besides, the check saw: first line)"
    assert guard.failure_text([FAKE, "b"], AssertionError("")) == FAKE + "; b"
