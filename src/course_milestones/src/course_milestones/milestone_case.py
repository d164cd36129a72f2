"""The base class of every milestone check: a failure's text is the check's own sentence.

unittest puts its own words before a check's message ("None is not true : ...",
"[] is not true : ..."); a student reads the sentence, not the assertion, so every check
turns that off here, once. A message that is a causes.Finding records its cause for the grader
(in the run's artifacts folder) when the assertion fails.
"""
import unittest

from course_milestones import causes
from course_checks.artifacts import artifact_dir


def _record(message: object) -> None:
    key = causes.of(message)
    if key:
        causes.record(artifact_dir(), key)


class MilestoneCase(unittest.TestCase):
    """A check's test case whose failure message is the message given to the assertion, alone."""

    longMessage = False

    def _formatMessage(self, msg, standardMsg):  # unittest calls it only for a failing assertion
        _record(msg)
        return super()._formatMessage(msg, standardMsg)

    def fail(self, msg=None):
        _record(msg)
        super().fail(msg)
