"""The `generated` step: the student's build made the messages, services and actions the text
defines (course_milestones.messages finds their generated classes without importing the student's
package); a missing one is named by the file the text has the student write."""
from __future__ import annotations

from typing import Dict, List

from course_milestones import messages
from course_milestones.steps.state import StepState, course_error, failed

# The messages genmsg makes of an action file.
ACTION_PARTS = ("Action", "Goal", "Result", "Feedback")


def generated(state: StepState, p: Dict, where: str) -> None:
    wanted = [("msg", str(n)) for n in p.get("messages") or []] + [("srv", str(n)) for n in p.get("services") or []] \
        + [("action", str(n)) for n in p.get("actions") or []]
    if not wanted:
        raise course_error(where, "generated names no message, service or action")
    problems: List[str] = []
    for kind, name in wanted:
        if "/" not in name:
            raise course_error(where, "%r: a %s is named pkg/Name" % (name, kind))
        pkg, base = name.split("/", 1)
        problem = _problem(kind, name)
        if problem:
            problems.append("%s/%s/%s.%s is not generated (%s: add it to add_%s_files() and generate_messages())"
                            % (pkg, kind, base, kind, problem, {"msg": "message", "srv": "service",
                                                                "action": "action"}[kind]))
    if problems:
        raise failed("not_generated", "; ".join(problems))


def _problem(kind: str, name: str) -> str:
    """Why the class(es) of `name` cannot be had, or ''."""
    try:
        if kind == "msg":
            messages.message_class(name)
        elif kind == "srv":
            messages.service_class(name)
        else:
            for part in ACTION_PARTS:
                messages.message_class(name + part)
    except messages.InterfaceError as err:
        return str(err)
    return ""
