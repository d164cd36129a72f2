"""Every check passes its run's gate (course_checks.run_gate) before its class set-up: a run the
grader started while the student's overlay was building does nothing with the student's
packages until the gate says go, and ends with its tests skipped when it says stop."""
import threading
import unittest

import pytest

from course_checks import run_gate
from course_milestones import milestone_case, guard
from course_milestones.milestone_case import MilestoneCase


@pytest.fixture(autouse=True)
def fresh_gate():
    milestone_case._gate_open.cache_clear()
    yield
    milestone_case._gate_open.cache_clear()


def _cases(seen):
    class OwnSetUp(MilestoneCase):  # like arch_check: its own setUpClass, no super()
        @classmethod
        def setUpClass(cls):
            seen.append("own set-up")

        def test_it(self):
            seen.append("test")

    class Inherited(MilestoneCase):  # no setUpClass of its own
        def test_it(self):
            seen.append("inherited test")

    @guard.judged
    class Judged(MilestoneCase):  # the trust guard's wrapper around the gated set-up
        @classmethod
        def setUpClass(cls):
            seen.append("judged set-up")

        def test_it(self):
            seen.append("judged test")
    return [OwnSetUp, Inherited, Judged]


def _run(cases):
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c) for c in cases)
    return unittest.TextTestRunner(stream=open("/dev/null", "w"), verbosity=0).run(suite)


def test_without_a_gate_every_check_starts_at_once(monkeypatch):
    monkeypatch.delenv(run_gate.ENV_VAR, raising=False)
    seen = []
    result = _run(_cases(seen))
    assert result.wasSuccessful() and not result.skipped
    assert seen == ["own set-up", "test", "inherited test", "judged set-up", "judged test"]


def test_a_stopped_gate_skips_every_test_and_runs_no_set_up(monkeypatch, tmp_path):
    gate = str(tmp_path / "gate")
    run_gate.decide(gate, False)
    monkeypatch.setenv(run_gate.ENV_VAR, gate)
    seen = []
    result = _run(_cases(seen))
    assert seen == [] and len(result.skipped) == 3 and not result.failures and not result.errors


def test_the_set_up_waits_until_the_gate_opens(monkeypatch, tmp_path):
    gate = str(tmp_path / "gate")
    monkeypatch.setenv(run_gate.ENV_VAR, gate)
    seen = []
    results = []
    runner = threading.Thread(target=lambda: results.append(_run(_cases(seen))))
    runner.start()
    runner.join(0.3)
    assert runner.is_alive() and seen == [], "a check went on before its gate was decided"
    run_gate.decide(gate, True)
    runner.join(10)
    assert not runner.is_alive() and results[0].wasSuccessful() and len(seen) == 5


def test_a_gate_that_says_nonsense_or_is_never_decided_is_an_error_not_a_pass(monkeypatch, tmp_path):
    gate = tmp_path / "gate"
    gate.write_text("maybe")
    with pytest.raises(run_gate.GateError):
        run_gate.wait({run_gate.ENV_VAR: str(gate)}, limit=1)
    with pytest.raises(run_gate.GateError):
        run_gate.wait({run_gate.ENV_VAR: str(tmp_path / "never")}, limit=0.1)
    monkeypatch.setenv(run_gate.ENV_VAR, str(gate))
    result = _run(_cases([]))
    assert len(result.errors) == 3 and not result.wasSuccessful()
