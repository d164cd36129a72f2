"""The trust policy (course_milestones.trusted) wired into a milestone check's own rospy.

A check calls `install([TURTLESIM])` right after rospy.init_node and before any student code
runs, and decorates its TestCase with `@judged`. From then on, in the check's process:

- Topics. rospy connects a subscriber to a publisher in one place:
  `rospy.impl.masterslave.ROSHandler._connect_topic(topic, pub_uri)`. The master's answer to
  registerSubscriber, every publisherUpdate the master sends (and any a student's process sends
  straight to the check's XML-RPC port) all end there, one call per publisher URI; the TCP
  connection that carries the data is opened only after it returns. So that method is wrapped:
  a publisher of a guarded topic at an untrusted URI is refused (no connection, no message ever
  reaches a subscriber of the check) and recorded as a violation. A topic that becomes guarded
  later (a turtle spawned after a student's node published its pose) has its untrusted
  connections closed when the master's update for the simulator's new publisher arrives.
- Services. Every rospy.ServiceProxy call asks the master for the provider's endpoint in
  `rospy.impl.tcpros_service.ServiceProxy._get_service_uri`, then connects to it. That method
  is wrapped: a guarded service whose endpoint is not the simulator's recorded one is not
  called (ServiceException with the violation sentence). course_checks.artifacts.save_canvas
  goes through it too, so a student's /turtlesim/snapshot is never asked for a path.
- Name takeovers (lookupNode gives a simulator's name another URI) are found at each look.

`@judged` makes each test fail with the violation sentences first, whatever else it saw.
Whatever the check does outside its process (`rosservice call`, `rostopic echo` as
subprocesses) is not covered; the final audit still names who registered what.
"""
from __future__ import annotations

import functools
import threading
import unittest
from typing import Callable, Iterable, List, Optional, Sequence

import rosgraph
import rospy
from rospy.impl import masterslave, tcpros_service
from rospy.impl.registration import get_topic_manager

from course_milestones.trusted import Graph, Simulator, TrustError, TrustPolicy
from course_checks.waiting import wait_for

CALLER = "/course_trust_guard"
RECORD_TIMEOUT_S = 30.0
RECORD_POLL_S = 0.05
# What a look at the master can raise: no answer (OSError), or an error answer.
LOOK_ERRORS = (OSError, rosgraph.MasterException)

_original_connect_topic = masterslave.ROSHandler._connect_topic
_original_get_service_uri = tcpros_service.ServiceProxy._get_service_uri
_active: Optional["Guard"] = None
_patch_lock = threading.Lock()


class Guard:
    """A TrustPolicy and the master it looks at."""

    def __init__(self, policy: TrustPolicy) -> None:
        self.policy = policy
        self.reported: List[str] = []   # sentences a verdict has already failed with

    # -- looking at the master ----------------------------------------------------------------------

    def look(self, topic: Optional[str] = None, services: Iterable[str] = (),
             simulators_services: bool = False) -> Graph:
        """One look at the master: every registration, the URIs of the simulators' names (and of
        the publishers of `topic`), and the endpoints of `services` (and of every service a
        simulator's name offers, with `simulators_services`). A fresh master proxy each time:
        rospy asks from several threads."""
        master = rosgraph.Master(CALLER)
        state = master.getSystemState()
        bare = Graph.from_system_state(state)
        names = set(self.policy.simulators)
        if topic is not None:
            names |= set(bare.publishers.get(topic, ()))
        node_uris = {}
        for name in sorted(names):
            try:
                node_uris[name] = master.lookupNode(name)
            except rosgraph.MasterException:
                continue  # not registered (any more)
        wanted = set(services)
        if simulators_services:
            for name in self.policy.simulators:
                wanted |= bare.offered_by(name)
        service_uris = {}
        for service in sorted(wanted):
            try:
                service_uris[service] = master.lookupService(service)
            except rosgraph.MasterException:
                continue
        return Graph.from_system_state(state, node_uris, service_uris)

    # -- the decisions rospy asks for ---------------------------------------------------------------

    def allows_connection(self, topic: str, pub_uri: str) -> bool:
        """May the check's subscriber to `topic` connect to `pub_uri`? Also closes the connections
        this look shows to be forbidden now. Without an answer from the master, only a trusted
        publisher is allowed."""
        if self.policy.trusts_uri(pub_uri) and self.policy.is_guarded_topic(topic):
            return True
        try:
            graph = self.look(topic=topic)
        except LOOK_ERRORS:
            return self.policy.trusts_uri(pub_uri)
        allowed = self.policy.may_connect(topic, pub_uri, graph)
        self.policy.observe(graph)  # a stolen simulator name shows at any look
        self.drop_untrusted(graph)
        return allowed

    def refusal(self, service: str, endpoint: str) -> Optional[str]:
        """None when the check may call `service` at `endpoint`, else why not (a sentence)."""
        try:
            graph = self.look()
        except LOOK_ERRORS as err:
            return "cannot ask the master who offers %s: %s" % (service, err)
        self.policy.observe(graph)
        return self.policy.call_refusal(service, endpoint, graph)

    def drop_untrusted(self, graph: Graph) -> None:
        """Close every connection of the check's subscribers to an untrusted publisher of a guarded
        topic (a topic can become guarded after the connection was made), each a violation."""
        manager = get_topic_manager()
        for topic in self.policy.guarded_topic_names():
            impl = manager.get_subscriber_impl(topic)
            untrusted = [c for c in (list(impl.connections) if impl is not None else [])
                         if not self.policy.trusts_uri(c.endpoint_id)]
            if not untrusted:
                continue
            try:
                named = self.look(topic=topic)  # who is at each URI, for the sentence
            except LOOK_ERRORS:
                named = graph
            for conn in untrusted:
                self.policy.may_connect(topic, conn.endpoint_id, named)
                conn.close()

    # -- the verdict --------------------------------------------------------------------------------

    def audit(self) -> List[str]:
        """Look at the whole graph (takeovers, who publishes and offers the guarded names, at which
        endpoints), close forbidden connections, and return every violation so far, preceded by
        the record's problem if it had one."""
        try:
            graph = self.look(services=self.policy.guarded_service_names(), simulators_services=True)
        except LOOK_ERRORS:
            return self.policy.verdict()  # the master is gone: what was seen stands
        self.policy.observe(graph)
        self.drop_untrusted(graph)
        return self.policy.verdict()


# -- the hooks in rospy ------------------------------------------------------------------------------

def _guarded_connect_topic(handler: masterslave.ROSHandler, topic: str, pub_uri: str):
    """ROSHandler._connect_topic, refusing what the active guard forbids (rospy's own return
    convention: code 0 is a failure it only logs, and it retries on the next update)."""
    guard = _active
    if guard is not None and not guard.allows_connection(topic, pub_uri):
        return 0, "the check's trust guard refused %s as a publisher of %s" % (pub_uri, topic), 0
    return _original_connect_topic(handler, topic, pub_uri)


def _guarded_get_service_uri(proxy: tcpros_service.ServiceProxy, request) -> str:
    """ServiceProxy._get_service_uri, raising ServiceException for a provider the active guard
    forbids, before any byte is sent to it."""
    endpoint = _original_get_service_uri(proxy, request)
    guard = _active
    if guard is not None:
        problem = guard.refusal(proxy.resolved_name, endpoint)
        if problem:
            raise rospy.ServiceException(problem)
    return endpoint


def _patch() -> None:
    masterslave.ROSHandler._connect_topic = _guarded_connect_topic
    tcpros_service.ServiceProxy._get_service_uri = _guarded_get_service_uri


def active() -> Optional[Guard]:
    """The guard installed in this process, if any."""
    return _active


def install(simulators: Sequence[Simulator], timeout: float = RECORD_TIMEOUT_S) -> Guard:
    """Record `simulators` (waiting up to `timeout` for each to register what it should), make
    their guard this process's and hook rospy. Call it after rospy.init_node and before starting
    any student code. When a simulator never gets ready, the guard keeps that as its problem and
    every @judged test fails with it: the check could not tell the simulator from a fake."""
    policy = TrustPolicy(simulators)
    guard = Guard(policy)

    def ready() -> Optional[Graph]:
        try:
            graph = guard.look(simulators_services=True)
        except LOOK_ERRORS:
            return None
        return None if policy.missing(graph) else graph
    graph = wait_for(ready, timeout, RECORD_POLL_S)
    try:
        if graph is None:
            raise TrustError("not ready")
        policy.record(graph, own_uri=rospy.get_node_uri())
    except TrustError:
        try:
            policy.fail_record(policy.missing(guard.look(simulators_services=True)))
        except LOOK_ERRORS as err:
            policy.fail_record(["the master did not answer: %s" % err])
    activate(guard)
    return guard


def activate(guard: Guard) -> None:
    """Make `guard` this process's and hook rospy (install does it; tests of the guard redo it
    after `uninstall`)."""
    global _active
    with _patch_lock:
        _patch()
        _active = guard


def uninstall() -> None:
    """Back to plain rospy (for tests of the guard itself)."""
    global _active
    with _patch_lock:
        _active = None
        masterslave.ROSHandler._connect_topic = _original_connect_topic
        tcpros_service.ServiceProxy._get_service_uri = _original_get_service_uri


# -- the verdict in a TestCase ----------------------------------------------------------------------

def failure_text(violations: Sequence[str], error: Optional[BaseException]) -> str:
    """The violations first, then (as an aside) what the check itself failed with."""
    text = "; ".join(violations)
    said = str(error).strip().splitlines()[0] if error is not None and str(error).strip() else ""
    return text + (" (besides, the check saw: %s)" % said if said else "")


def _judge(error: Optional[BaseException], failure: type, only_new: bool = False) -> None:
    """Raise `failure` with the violations when the active guard has some (only those no verdict
    reported yet with `only_new`); `error` is what the step raised, if anything."""
    guard = _active
    if guard is None:
        return
    violations = guard.audit()
    if only_new:
        violations = [v for v in violations if v not in guard.reported]
    if violations:
        guard.reported.extend(v for v in violations if v not in guard.reported)
        raise failure(failure_text(violations, error)) from None


def _wrap_step(step: Callable, failure_of: Callable[[object], type], after: bool) -> Callable:
    """`step` (a test or a fixture) judged by the guard: always afterwards when `after`, else only
    when it raised."""
    @functools.wraps(step)
    def judged_step(self_or_cls, *args, **kwargs):
        failure = failure_of(self_or_cls)
        try:
            result = step(self_or_cls, *args, **kwargs)
        except unittest.SkipTest:
            raise
        except Exception as err:  # noqa: BLE001 - any failure of the check yields to a violation
            _judge(err, failure)
            raise
        if after:
            _judge(None, failure, only_new=step.__name__.startswith("tearDown"))
        return result
    return judged_step


def judged(cls: type) -> type:
    """Class decorator for a milestone's TestCase: each test, when it ends (passed or failed),
    fails with the guard's violations if there are any; setUp/setUpClass failures give way to
    them too; tearDown/tearDownClass fail with violations no test has reported yet (a fake
    snapshot service found while saving the canvas)."""
    def instance_failure(obj) -> type:
        return obj.failureException

    def class_failure(klass) -> type:
        return klass.failureException
    for name, member in list(vars(cls).items()):
        if name.startswith("test") and callable(member):
            setattr(cls, name, _wrap_step(member, instance_failure, after=True))
        elif name in ("setUp", "tearDown") and callable(member):
            setattr(cls, name, _wrap_step(member, instance_failure, after=name == "tearDown"))
        elif name in ("setUpClass", "tearDownClass") and isinstance(member, classmethod):
            setattr(cls, name, classmethod(_wrap_step(member.__func__, class_failure,
                                                      after=name == "tearDownClass")))
    return cls
