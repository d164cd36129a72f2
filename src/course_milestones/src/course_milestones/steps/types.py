"""Message and service classes for the steps (course_milestones.messages builds them without
importing a student's code), with the blame put where it belongs: a type the course file names
that does not exist is the course file's mistake; one of the student's own packages (the
milestone's `packages`), or one the student's node declared, that cannot be had is not generated."""
from __future__ import annotations

from course_milestones import messages
from course_milestones.steps.state import StepFailed, StepState, course_error, failed


def load(kind: str, type_name: str, state: StepState, where: str, students: bool = False) -> type:
    """The class of `type_name` (kind "msg" or "srv"); `students`: the type came from the student's node."""
    loader = messages.message_class if kind == "msg" else messages.service_class
    try:
        return loader(type_name)
    except messages.InterfaceError as err:
        raise _blame(kind, type_name, err, state, where, students) from None


def _blame(kind: str, type_name: str, err: Exception, state: StepState, where: str, students: bool) -> StepFailed:
    pkg = type_name.split("/")[0]
    if students or pkg in state.packages:
        return failed("not_generated", "%s %s cannot be loaded: %s" % ("message" if kind == "msg" else "service",
                                                                       type_name, err))
    return course_error(where, "%s type %s cannot be loaded: %s" % ("message" if kind == "msg" else "service",
                                                                    type_name, err))
