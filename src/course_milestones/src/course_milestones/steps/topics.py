"""The topic steps: `publishes` and `subscribes` (what the student's node does, seen at the master
and, for a publisher, in the messages it sends: type, rate, fields) and `publish` (an action: the
check sends messages, e.g. velocity commands to the student's node)."""
from __future__ import annotations

import time
from typing import Dict, List, Optional, Sequence, Tuple

import genpy
import rospy

from course_milestones import students
from course_milestones.discovery import own_names, topic_types
from course_milestones.steps import predicates
from course_milestones.steps.state import StepState, course_error, failed
from course_milestones.steps.types import load
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

# With a rate to judge, messages are gathered until there are this many and they span this long.
RATE_MESSAGES = 5
RATE_SPAN_S = 1.0
CONNECT_S = 5.0   # s: how long `publish` waits for the topic's subscribers to connect


class TimedRecorder(TopicRecorder):
    """A TopicRecorder that also keeps when each message arrived (time.monotonic)."""

    def __init__(self, topic: str, msg_type) -> None:
        self._arrivals: List[float] = []
        super().__init__(topic, msg_type)

    def _on_msg(self, msg) -> None:
        with self._lock:
            self._messages.append(msg)
            self._arrivals.append(time.monotonic())

    def received(self, senders: Optional[Sequence[str]]) -> List[Tuple[float, object]]:
        """(arrival, message) of the messages from `senders` (node names; anyone's when None)."""
        with self._lock:
            pairs = list(zip(self._arrivals, self._messages))
        return [(t, m) for t, m in pairs if senders is None or sender(m) in senders]


def sender(message) -> str:
    """The node that sent a received message (rospy keeps the publisher's connection header)."""
    return (getattr(message, "_connection_header", None) or {}).get("callerid", "")


def check_fields(fields: Dict, where: str) -> None:
    for path, predicate in (fields or {}).items():
        wrong = predicates.problem(predicate)
        if wrong:
            raise course_error(where, "fields.%s: %s" % (path, wrong))


def _not_registered(state: StepState, node: Optional[str], nodes, topic: str, kind: str) -> Exception:
    """Why no node of `nodes` (those of the step's `node`) publishes (kind "publishes") or
    subscribes to `topic`."""
    regs = state.registered(nodes)
    who = state.who(nodes)
    if nodes is not None and not regs:
        started = state.find(node)  # a node of a started process exited; one no step started never ran
        cause = "not_started" if not nodes else state.exit_cause(started) if started else "not_running"
        return failed(cause, "%s is not running, so nothing %s %s" % (who, kind, topic))
    other = sorted({n for r in regs for n in own_names(getattr(r, kind))})
    if other:
        return failed("wrong_topic", "%s %s %s, not %s" % (who, kind, ", ".join(other), topic))
    cause = "not_published" if kind == "publishes" else "not_subscribed"
    return failed(cause, "%s %s nothing: no %s on %s" % (
        who, kind, "publisher" if kind == "publishes" else "subscriber", topic) if nodes is not None
        else "no node %s %s" % (kind, topic))


def registration(state: StepState, p: Dict, where: str, kind: str):
    """Wait for the step's node to publish (or subscribe to) the step's topic; the nodes that do."""
    topic = p["topic"]
    nodes = state.nodes(p.get("node"), where)
    started = state.find(p.get("node"))  # None: a node no step started (/turtlesim)

    def doing() -> List[str]:
        return [r.node for r in state.registered(nodes) if topic in getattr(r, kind)]

    def exited() -> bool:
        return started is not None and not started.process.node.running()
    # no waiting on a process that is gone: it does not come back, and how long it ran is no matter
    found = wait_for(lambda: doing() or exited(), float(p.get("within") or 0), 0.1)
    found = found if isinstance(found, list) else doing()
    if not found and started is not None and exited():  # the started process exited: say how
        raise failed(state.exit_cause(started), "`%s` exited with status %s, so nothing %s %s%s" % (
            started.command, started.process.node.proc.returncode, kind, topic,
            students.last_words(started.process)))
    if not found and nodes == ():  # the started process runs, but no node (any more)
        started = state.process(p.get("node"), where)
        raise failed("not_started", "`%s` runs no node, so nothing %s %s" % (started.command, kind, topic))
    if not found:
        raise _not_registered(state, p.get("node"), nodes, topic, kind)
    return found


def subscribes(state: StepState, p: Dict, where: str) -> None:
    registration(state, p, where, "subscribes")


def publishes(state: StepState, p: Dict, where: str) -> None:
    topic, within = p["topic"], float(p.get("within") or 0)
    check_fields(p.get("fields"), where)
    if p.get("type"):
        load("msg", p["type"], state, where)
    senders = registration(state, p, where, "publishes")
    actual = topic_types().get(topic, "")
    if p.get("type") and actual != p["type"]:
        raise failed("wrong_type", "%s publishes %s of type %s; the text's type is %s" % (
            ", ".join(senders), topic, actual or "(unknown)", p["type"]))
    recorder = TimedRecorder(topic, load("msg", actual, state, where, students=True))
    try:
        received = _gather(recorder, senders, p, within)
    finally:
        recorder.unregister()
    who = ", ".join(senders)
    count = int(p.get("count") or 1)
    if not received:
        raise failed("silent", "%s advertises %s but sent no message on it within %g s" % (who, topic, within))
    if len(received) < count:
        raise failed("wrong_rate", "%s sent %d message(s) on %s within %g s; the text asks for %d" % (
            who, len(received), topic, within, count))
    _judge_fields(who, topic, received, p.get("fields") or {}, bool(p.get("type")), where)
    measured = predicates.rate([t for t, _ in received])
    wrong = predicates.rate_problem(measured, p.get("min_rate"), p.get("max_rate"))
    if wrong:
        raise failed("wrong_rate", "on %s, %s (%d messages over %.1f s)" % (
            topic, wrong.replace("it publishes", "%s publishes" % who), len(received),
            received[-1][0] - received[0][0]))


def _gather(recorder: TimedRecorder, senders: Sequence[str], p: Dict, within: float):
    """The messages `senders` send within `within` s: `count` of them, more with a rate to judge."""
    count = int(p.get("count") or 1)
    rated = p.get("min_rate") is not None or p.get("max_rate") is not None

    def enough():
        got = recorder.received(senders)
        if len(got) < (max(count, RATE_MESSAGES) if rated else count):
            return False
        return not rated or got[-1][0] - got[0][0] >= RATE_SPAN_S
    wait_for(enough, within, 0.05)
    return recorder.received(senders)


def _judge_fields(who: str, topic: str, received, fields: Dict, typed: bool, where: str) -> None:
    for index, (_, message) in enumerate(received):
        for path, predicate in fields.items():
            try:
                value = predicates.field(message, path)
            except predicates.FieldMissing as err:
                if typed:
                    raise course_error(where, "fields.%s: %s" % (path, err)) from None
                raise failed("wrong_value", "%s: the messages on %s have no %s: %s" % (who, topic, path, err)) \
                    from None
            verdict = predicates.holds(predicate, value)
            if not verdict.holds:
                raise failed("wrong_value", "message %d of %s on %s: %s %s (the message: %s)" % (
                    index + 1, who, topic, path, verdict.text, predicates.describe(message)))


def publish(state: StepState, p: Dict, where: str) -> None:
    cls = load("msg", p["type"], state, where)
    message = cls()
    try:
        genpy.message.fill_message_args(message, [p.get("message") or {}])
    except (genpy.MessageException, ValueError, TypeError, KeyError) as err:
        raise course_error(where, "message %r does not fit %s: %s" % (p.get("message"), p["type"], err)) from None
    rate, duration = float(p.get("rate") or 10.0), float(p.get("duration") or 0.0)
    if rate <= 0:
        raise course_error(where, "rate must be more than 0 Hz, not %g" % rate)
    state.action("publishing %s on %s" % (predicates.describe(message), p["topic"]))
    publisher = rospy.Publisher(p["topic"], cls, queue_size=10)
    try:
        subscribed = [r for r in state.registered(None) if p["topic"] in r.subscribes]
        if subscribed:
            wait_for(lambda: publisher.get_num_connections() >= len(subscribed), CONNECT_S, 0.02)
        end = time.monotonic() + duration
        ticks = rospy.Rate(rate)
        publisher.publish(message)
        while time.monotonic() < end and not rospy.is_shutdown():
            ticks.sleep()
            publisher.publish(message)
    finally:
        state.closers.append(publisher.unregister)  # at the end: what is queued still goes out
