"""What a milestone is: one gradable milestone of a course, read from its course file
(course_format.course_file), checked by a rostest: a Python check's, or the generic
`run_steps` running the milestone's steps."""
from __future__ import annotations

from typing import Any, Dict, NamedTuple, Tuple


class Step(NamedTuple):
    """One step of a data milestone: a primitive of course_format.schema."""

    primitive: str
    params: Dict[str, Any]  # every parameter of the primitive, defaults filled in
    where: str  # "course.yaml:14 (milestones[1].steps[2])", for a message about this step


class Equivalent(NamedTuple):
    """A mutant of the milestone's reference (course-lint's, docs/course_lint.md) that no check can
    kill, because the text allows what it changes: `equivalent: {NAME: REASON}` in course.yaml.
    course-lint counts it apart from the survivors, and reports an annotation that names no
    surviving mutant as an error."""

    mutant: str  # course-lint's name of it, OPERATOR_N (e.g. rate_div10_1)
    reason: str  # why no check can kill it, for a reviewer
    line: int  # the annotation's line in the course file


class Milestone(NamedTuple):
    """One gradable milestone.

    name: short id used on the command line (`--only NAME`), in the gradebook and in JUnit names.
    title: what the milestone is, in the text's words.
    text: the course text and section it comes from (e.g. "002 Lab 2, checkpoint 1").
    test_file: a Python check's rostest file: a name under course_milestones/test/, or the path of
        one in the course's checks/ folder; "" for a data milestone (steps).
    packages: the package names the text makes the student write; the milestone grades a
        submission only if the submission holds at least one of them. Empty: the milestone checks
        the course workspace itself (simulators, tools) and is graded for the reference only.
    points: the milestone's weight in the gradebook.
    steps: a data milestone's steps, in order.
    world: the trusted nodes a data milestone starts before the student's (schema.WORLDS).
    course_file: the course.yaml it comes from.
    time_limit: seconds the milestone's rostest may take.
    equivalent: the mutants of its reference that course-lint is told no check can kill.
    """

    name: str
    title: str
    text: str
    test_file: str
    packages: Tuple[str, ...] = ()
    points: float = 10.0
    steps: Tuple[Step, ...] = ()
    world: Tuple[str, ...] = ()
    course_file: str = ""
    time_limit: float = 90.0
    equivalent: Tuple[Equivalent, ...] = ()
