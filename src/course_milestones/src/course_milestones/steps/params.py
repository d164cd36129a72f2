"""The parameter steps: `set_param` (as `rosparam set NAME VALUE`: the value as the course file
gives it, already YAML) and `param_is` (a parameter on the server satisfies a predicate)."""
from __future__ import annotations

from typing import Dict

import rospy

from course_milestones.steps import predicates
from course_milestones.steps.state import StepState, course_error, failed
from course_checks.waiting import wait_for

NOT_SET = object()


def set_param(state: StepState, p: Dict, where: str) -> None:
    state.action("`rosparam set %s %s`" % (p["name"], p["value"]))
    rospy.set_param(p["name"], p["value"])


def param_is(state: StepState, p: Dict, where: str) -> None:
    wrong = predicates.problem(p["expect"])
    if wrong:
        raise course_error(where, "expect: %s" % wrong)

    def value():
        return rospy.get_param(p["name"], NOT_SET)
    if wait_for(lambda: value() is not NOT_SET and predicates.holds(p["expect"], value()).holds,
                float(p.get("within") or 0), 0.1):
        return
    now = value()
    if now is NOT_SET:
        raise failed("wrong_value", "parameter %s is not set; the text expects it %s" % (
            p["name"], predicates.expectation(p["expect"])))
    raise failed("wrong_value", "parameter %s %s" % (p["name"], predicates.holds(p["expect"], now).text))
