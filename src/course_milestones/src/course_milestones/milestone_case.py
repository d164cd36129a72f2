"""The base class of every milestone check: a failure's text is the check's own sentence.

unittest puts its own words before a check's message ("None is not true : ...",
"[] is not true : ..."); a student reads the sentence, not the assertion, so every check
turns that off here, once. A message that is a causes.Finding records its cause for the grader
(in the run's artifacts folder) when the assertion fails; a check of the course's own tools (no
student package) names the cause of its every failure once, as `failure_cause`. Where a check
cannot call self.fail (a setUpClass, a helper without the test case), it raises `failure(...)`.

Every check's class set-up first passes the run's gate (course_checks.run_gate): a run the grader
started while the student's overlay was still building waits there, before any check code that
looks at the student's packages; a voided run ends there, its tests skipped. Subclasses need not
call super(): each setUpClass a subclass defines is wrapped when the class is made.
"""
import functools
import unittest
from typing import Optional

from course_checks import run_gate
from course_format import causes
from course_checks.artifacts import artifact_dir


def _record(message: object, default: str = "") -> None:
    key = causes.of(message, default)
    if key:
        causes.record(artifact_dir(), key)


def failure(message: str) -> AssertionError:
    """The failure to raise with `message` (a causes.Finding) where self.fail cannot be called; its
    cause is recorded as fail records it."""
    _record(message)
    return AssertionError(message)


@functools.lru_cache(maxsize=1)
def _gate_open() -> bool:
    """Whether this run goes on: asked once per process (several classes, one gate)."""
    return run_gate.wait()


def _pass_gate() -> None:
    if not _gate_open():
        raise unittest.SkipTest("the grader voided this run before it began (its results are discarded)")


class MilestoneCase(unittest.TestCase):
    """A check's test case whose failure message is the message given to the assertion, alone."""

    longMessage = False
    # The cause of a failure whose message carries none: set only by the checks of the course's own
    # tools, whose assertions keep unittest's words (course_tools).
    failure_cause = ""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        own = cls.__dict__.get("setUpClass")
        if isinstance(own, classmethod):
            body = own.__func__

            @functools.wraps(body)
            def gated(klass):
                _pass_gate()
                body(klass)
            cls.setUpClass = classmethod(gated)

    @classmethod
    def setUpClass(cls):
        _pass_gate()

    def _formatMessage(self, msg, standardMsg):  # unittest calls it only for a failing assertion
        _record(msg, self.failure_cause)
        return super()._formatMessage(msg, standardMsg)

    def fail(self, msg=None):
        _record(msg, self.failure_cause)
        super().fail(msg)

    def fail_on(self, problem: Optional[str]) -> None:
        """Fail with `problem`, a sentence from a helper that returns one when something is wrong
        (None: nothing is)."""
        if problem:
            self.fail(problem)
