"""What a milestone is: a rostest in course_milestones that checks one milestone of a course text."""
from __future__ import annotations

from typing import NamedTuple, Tuple


class Milestone(NamedTuple):
    """One gradable milestone.

    name: short id used on the command line (`--only NAME`), in the gradebook and in JUnit names.
    title: what the milestone is, in the text's words.
    text: the course text and section it comes from (e.g. "002 Lab 2, checkpoint 1").
    test_file: the rostest file under course_milestones/test/.
    packages: the package names the text makes the student write; the milestone grades a
        submission only if the submission holds at least one of them. Empty: the milestone checks
        the course workspace itself (simulators, tools) and is graded for the reference only.
    points: the milestone's weight in the gradebook.
    """

    name: str
    title: str
    text: str
    test_file: str
    packages: Tuple[str, ...] = ()
    points: float = 10.0
