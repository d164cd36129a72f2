"""The service steps: `advertises` (the student's node offers a service, of a type, seen at the
master) and `call` (the check calls it with the text's request, keeps the answer's fields it is
told to save for later steps, and judges the answer's fields)."""
from __future__ import annotations

import threading
from typing import Dict, List

import genpy
import rosservice
import rospy

from course_format import saved
from course_milestones.discovery import own_names
from course_milestones.steps import predicates
from course_milestones.steps.state import StepState, course_error, failed
from course_milestones.steps.types import load
from course_checks.waiting import wait_for


def service_type(service: str) -> str:
    """The type the service's provider declares ('' when it cannot be asked)."""
    try:
        return rosservice.get_service_type(service) or ""
    except Exception:  # noqa: BLE001 - the provider went away, or answered no header
        return ""


def advertises(state: StepState, p: Dict, where: str) -> None:
    service = p["service"]
    if p.get("type"):
        load("srv", p["type"], state, where)
    nodes = state.nodes(p.get("node"), where)

    def offering() -> List[str]:
        return [r.node for r in state.registered(nodes) if service in r.services]
    found = wait_for(offering, float(p.get("within") or 0), 0.1)
    if not found:
        regs = state.registered(nodes)
        other = sorted({n for r in regs for n in own_names(r.services)})
        raise failed("no_service", "%s offers no service %s%s" % (
            state.who(nodes) if nodes is not None else "no node", service,
            " (it offers %s)" % ", ".join(other) if other else ""))
    declared = service_type(service)
    if p.get("type") and declared != p["type"]:
        raise failed("wrong_type", "%s offers %s of type %s; the text's type is %s" % (
            ", ".join(found), service, declared or "(unknown)", p["type"]))


def call(state: StepState, p: Dict, where: str) -> None:
    """Its `expect` may name what this call saves (${NAME}): it is resolved once the answer is in."""
    service, within = p["service"], float(p.get("within") or 0)
    for name, predicate in (p.get("expect") or {}).items():
        wrong = None if saved.references(predicate) else predicates.problem(predicate)
        if wrong:
            raise course_error(where, "expect.%s: %s" % (name, wrong))
    for name, path in (p.get("save") or {}).items():
        if not isinstance(path, str) or not saved.NAME.fullmatch(str(name)):
            raise course_error(where, "save.%s: save NAME: FIELD, a name of letters, digits and _ and the answer's "
                                      "field" % (name,))
    state.action("calling %s" % service)
    try:
        rospy.wait_for_service(service, within)
    except rospy.ROSException:
        offered = sorted({n for r in state.registered(None) for n in own_names(r.services)})
        raise failed("no_service", "no service %s within %g s (offered: %s)" % (
            service, within, ", ".join(offered) or "none")) from None
    srv_class = load("srv", service_type(service) or "?/?", state, where, students=True)
    request = srv_class._request_class()
    try:
        genpy.message.fill_message_args(request, [p.get("request") or {}])
    except (genpy.MessageException, ValueError, TypeError, KeyError) as err:
        raise course_error(where, "request %r does not fit %s: %s" % (p.get("request"), srv_class._type, err)) \
            from None
    answer = _answer(service, srv_class, request, within)
    if isinstance(answer, Exception):
        raise failed("wrong_answer", "calling %s with %s failed: %s" % (
            service, predicates.describe(request), answer))
    if answer is None:
        raise failed("wrong_answer", "%s did not answer %s within %g s" % (service, predicates.describe(request),
                                                                           within))
    for name, path in (p.get("save") or {}).items():
        try:
            state.saved[name] = predicates.field(answer, path)
        except predicates.FieldMissing as err:
            raise failed("wrong_answer", "%s's answer has no %s: %s" % (service, path, err)) from None
    try:
        expect = saved.resolve_predicates("call", p.get("expect") or {}, state.saved)
    except saved.Unknown as err:
        raise course_error(where, "expect names %s, which no step before it saved" % err) from None
    for path, predicate in expect.items():
        wrong = predicates.problem(predicate)
        if wrong:
            raise course_error(where, "expect.%s: %s" % (path, wrong))
        try:
            value = predicates.field(answer, path)
        except predicates.FieldMissing as err:
            raise failed("wrong_answer", "%s's answer has no %s: %s" % (service, path, err)) from None
        verdict = predicates.holds(predicate, value)
        if not verdict.holds:
            raise failed("wrong_answer", "%s answered %s to %s: %s %s" % (
                service, predicates.describe(answer), predicates.describe(request), path, verdict.text))


def _answer(service: str, srv_class: type, request, within: float):
    """The service's response, the exception its call raised, or None when it did not answer in
    `within` s (a server that never returns must not hold the milestone to its time limit)."""
    result: list = []

    def ask() -> None:
        try:
            result.append(rospy.ServiceProxy(service, srv_class)(request))
        except Exception as err:  # noqa: BLE001 - the server's exception, a refused call: the answer
            result.append(err)
    thread = threading.Thread(target=ask, daemon=True)
    thread.start()
    thread.join(within)
    return result[0] if result else None
