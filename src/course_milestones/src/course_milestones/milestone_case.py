"""The base class of every milestone check: a failure's text is the check's own sentence.

unittest puts its own words before a check's message ("None is not true : ...",
"[] is not true : ..."); a student reads the sentence, not the assertion, so every check
turns that off here, once.
"""
import unittest


class MilestoneCase(unittest.TestCase):
    """A check's test case whose failure message is the message given to the assertion, alone."""

    longMessage = False
