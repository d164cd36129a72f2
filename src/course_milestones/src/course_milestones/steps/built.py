"""The `generated` step: the student's build made the messages, services and actions the text
defines (course_milestones.messages finds their generated classes without importing the student's
package); a missing one is named by the file the text has the student write."""
from __future__ import annotations

from typing import Dict, List

from course_milestones import messages
from course_milestones.fields import field_problems, slots_of
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
    wrong = [w for name, layout in (p.get("layouts") or {}).items() for w in layout_problems(name, layout)]
    if wrong:
        raise failed("wrong_type", "; ".join(wrong))


def layout_problems(name: str, layout: Dict) -> List[str]:
    """How the generated `name`'s fields differ from the text's `layout` (a service's: its request's
    and response's), in the words a student fixes them by ("Person.msg: age is float32, ...")."""
    base = name.split("/", 1)[-1]
    if set(layout) == {"request", "response"} and all(isinstance(v, dict) for v in layout.values()):
        srv = messages.service_class(name)
        return (field_problems("%s.srv request" % base, layout["request"], slots_of(srv._request_class))
                + field_problems("%s.srv response" % base, layout["response"], slots_of(srv._response_class)))
    return field_problems("%s.msg" % base, layout, slots_of(messages.message_class(name)))


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
