"""The trust policy of milestone checks (course_milestones.trusted), on hand-made looks at the master:
whom it trusts, what it guards, what it refuses, and the sentences a student reads."""
from __future__ import annotations

from typing import Dict, Iterable, Optional

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from course_milestones.trusted import (GAZEBO, SHARED_TOPICS, TURTLESIM, Graph, Simulator, TrustError,
                                       TrustPolicy)

SIM_URI = "http://localhost:40001/"
SIM_SRV = "rosrpc://localhost:40002"
CHECK_URI = "http://localhost:40003/"
FAKE_URI = "http://localhost:45555/"
FAKE_SRV = "rosrpc://localhost:45556"
TURTLESIM_TOPICS = TURTLESIM.topics + ("/rosout",)
TURTLESIM_SERVICES = TURTLESIM.services + ("/turtlesim/get_loggers", "/turtlesim/set_logger_level")


def graph(publishers: Optional[Dict[str, Iterable[str]]] = None, providers: Optional[Dict[str, Iterable[str]]] = None,
          node_uris: Optional[Dict[str, str]] = None, service_uris: Optional[Dict[str, str]] = None) -> Graph:
    return Graph({t: frozenset(n) for t, n in (publishers or {}).items()},
                 {s: frozenset(n) for s, n in (providers or {}).items()},
                 dict(node_uris or {}), dict(service_uris or {}))


def turtlesim_graph(extra_publishers: Optional[Dict[str, Iterable[str]]] = None,
                    extra_providers: Optional[Dict[str, Iterable[str]]] = None,
                    node_uris: Optional[Dict[str, str]] = None,
                    service_uris: Optional[Dict[str, str]] = None) -> Graph:
    """turtlesim at SIM_URI with every topic and service it registers at start, plus extra
    publishers; an extra provider replaces the service's (the master keeps one per service)."""
    publishers: Dict[str, set] = {t: {"/turtlesim"} for t in TURTLESIM_TOPICS}
    providers: Dict[str, set] = {s: {"/turtlesim"} for s in TURTLESIM_SERVICES}
    for name, nodes in (extra_publishers or {}).items():
        publishers.setdefault(name, set()).update(nodes)
    providers.update({name: set(nodes) for name, nodes in (extra_providers or {}).items()})
    uris = {"/turtlesim": SIM_URI}
    uris.update(node_uris or {})
    endpoints = {s: SIM_SRV for s in TURTLESIM_SERVICES}
    endpoints.update(service_uris or {})
    return graph(publishers, providers, uris, endpoints)


def recorded() -> TrustPolicy:
    policy = TrustPolicy([TURTLESIM])
    policy.record(turtlesim_graph(), own_uri=CHECK_URI)
    return policy


# -- recording -----------------------------------------------------------------------------------

def test_record_trusts_the_simulator_by_uri_and_guards_what_it_registered():
    policy = recorded()
    assert policy.trusted_uris == {"/turtlesim": SIM_URI}
    assert policy.trusted_endpoints == {SIM_SRV: "/turtlesim"}
    assert set(policy.guarded_topics) == set(TURTLESIM.topics)  # /rosout is everyone's
    assert set(policy.guarded_services) == set(TURTLESIM_SERVICES)
    assert policy.verdict() == []


def test_record_waits_for_everything_the_simulator_must_register():
    policy = TrustPolicy([TURTLESIM])
    assert policy.missing(graph()) == ["/turtlesim is not registered"]
    partial = graph({"/turtle1/pose": {"/turtlesim"}}, {"/spawn": {"/turtlesim"}}, {"/turtlesim": SIM_URI},
                    {"/spawn": SIM_SRV})
    missing = policy.missing(partial)
    assert len(missing) == 1 and "/turtle1/color_sensor" in missing[0] and "/turtle1/teleport_absolute" in missing[0]
    assert "/turtle1/pose" not in missing[0] and "/spawn," not in missing[0]
    with pytest.raises(TrustError):
        policy.record(partial)
    assert policy.verdict()[0].startswith("the check could not record the simulator before your code ran")
    assert policy.missing(turtlesim_graph()) == []


def test_a_record_without_service_endpoints_is_not_ready():
    unresolved = turtlesim_graph()
    unresolved = Graph(unresolved.publishers, unresolved.providers, unresolved.node_uris, {})
    assert TrustPolicy([TURTLESIM]).missing(unresolved) == ["the services of /turtlesim were not looked up"]


def test_fail_record_makes_every_verdict_fail():
    policy = TrustPolicy([GAZEBO])
    policy.fail_record(["/gazebo is not registered"])
    assert policy.verdict() == [policy.problem] and "/gazebo is not registered" in policy.problem


# -- topics --------------------------------------------------------------------------------------

def test_a_fake_pose_publisher_is_refused_and_named():
    policy = recorded()
    look = turtlesim_graph({"/turtle1/pose": {"/fake_pose"}}, node_uris={"/fake_pose": FAKE_URI})
    assert policy.may_connect("/turtle1/pose", SIM_URI, look)
    assert not policy.may_connect("/turtle1/pose", FAKE_URI, look)
    assert policy.violations == ["your node /fake_pose publishes /turtle1/pose, which only turtlesim may publish: "
                                 "the check believes the simulator alone, so remove that publisher"]


def test_an_unknown_publisher_is_refused_by_its_uri():
    policy = recorded()
    assert not policy.may_connect("/turtle1/color_sensor", FAKE_URI, turtlesim_graph())
    assert policy.violations[0].startswith("a node of yours (at %s) publishes /turtle1/color_sensor, which only "
                                           "turtlesim may publish" % FAKE_URI)


def test_the_students_own_topics_and_rosout_are_not_guarded():
    policy = recorded()
    look = turtlesim_graph({"/turtle1/cmd_vel": {"/teleop"}, "/rosout": {"/teleop"}}, node_uris={"/teleop": FAKE_URI})
    assert policy.may_connect("/turtle1/cmd_vel", FAKE_URI, look)
    assert policy.may_connect("/rosout", FAKE_URI, look)
    assert policy.observe(look) == [] and policy.verdict() == []


def test_the_checks_own_publications_are_trusted():
    policy = recorded()
    assert policy.may_connect("/turtle1/pose", CHECK_URI, turtlesim_graph())
    assert policy.trusts_uri(CHECK_URI) and not policy.trusts_uri(FAKE_URI)


def test_a_spawned_turtles_topics_become_guarded_when_the_simulator_publishes_them():
    policy = recorded()
    before = turtlesim_graph({"/turtle2/pose": {"/early"}}, node_uris={"/early": FAKE_URI})
    assert policy.may_connect("/turtle2/pose", FAKE_URI, before), "no simulator publishes it yet"
    after = turtlesim_graph({"/turtle2/pose": {"/early", "/turtlesim"}}, node_uris={"/early": FAKE_URI})
    assert not policy.may_connect("/turtle2/pose", FAKE_URI, after)
    assert "your node /early publishes /turtle2/pose" in policy.violations[0]


def test_a_taken_over_name_is_a_violation_and_teaches_nothing():
    policy = recorded()
    stolen = turtlesim_graph({"/turtle1/cmd_vel": {"/turtlesim"}}, node_uris={"/turtlesim": FAKE_URI})
    new = policy.observe(stolen)
    assert new == ["a node of yours took the name /turtlesim, which is turtlesim's (now at %s): ROS shuts a node "
                   "down when another registers under its name, so give your node a name of its own" % FAKE_URI]
    assert "/turtle1/cmd_vel" not in policy.guarded_topics
    assert not policy.may_connect("/turtle1/pose", FAKE_URI, stolen), "the new /turtlesim is not the simulator"


# -- services ------------------------------------------------------------------------------------

def test_a_students_service_under_a_simulator_name_is_refused():
    policy = recorded()
    displaced = turtlesim_graph(extra_providers={"/turtle1/teleport_absolute": {"/fake_srv"}})
    assert policy.may_call("/spawn", SIM_SRV, displaced)
    assert not policy.may_call("/turtle1/teleport_absolute", FAKE_SRV, displaced), "guarded since the record"
    assert policy.violations == ["your node /fake_srv offers the service /turtle1/teleport_absolute, which only "
                                 "turtlesim may offer: the check calls the simulator alone, so remove that service"]


def test_a_service_registered_under_the_simulators_name_at_another_endpoint_is_refused():
    policy = recorded()
    forged = turtlesim_graph(service_uris={"/turtlesim/snapshot": FAKE_SRV})
    assert not policy.may_call("/turtlesim/snapshot", FAKE_SRV, forged)
    assert policy.violations[0].startswith("a node of yours offers the service /turtlesim/snapshot under turtlesim's "
                                           "name /turtlesim (at %s)" % FAKE_SRV)
    assert policy.observe(forged) == [], "the same sentence is not repeated"


def test_the_students_own_services_may_be_called():
    policy = recorded()
    look = turtlesim_graph(extra_providers={"/turtle1/patrol": {"/patrol"}})
    assert policy.may_call("/turtle1/patrol", FAKE_SRV, look)
    assert policy.observe(look) == []


def test_observe_names_fake_publishers_and_providers_once():
    policy = recorded()
    look = turtlesim_graph({"/turtle1/pose": {"/fake"}}, {"/clear": {"/fake"}}, node_uris={"/fake": FAKE_URI},
                           service_uris={"/clear": FAKE_SRV})
    first = policy.observe(look)
    assert len(first) == 2
    assert any(s.startswith("your node /fake publishes /turtle1/pose") for s in first)
    assert any(s.startswith("your node /fake offers the service /clear") for s in first)
    assert policy.observe(look) == [] and policy.violations == first


# -- properties ----------------------------------------------------------------------------------

NAMES = st.sampled_from(["/turtle1/pose", "/turtle1/color_sensor", "/turtle2/pose", "/turtle1/cmd_vel", "/rosout",
                         "/chatter", "/turtlesim/image"])
NODES = st.sampled_from(["/turtlesim", "/fake", "/mybot_color", "/teleop"])
URIS = st.sampled_from([SIM_URI, FAKE_URI, CHECK_URI, "http://localhost:47777/"])


@st.composite
def looks(draw) -> Graph:
    """A look at the master: turtlesim (sometimes under a stolen URI) and students' nodes, with any
    topics each."""
    publishers: Dict[str, set] = {}
    for _ in range(draw(st.integers(0, 8))):
        publishers.setdefault(draw(NAMES), set()).add(draw(NODES))
    uris = {n: draw(URIS) for n in ("/fake", "/mybot_color", "/teleop")}
    uris["/turtlesim"] = draw(st.sampled_from([SIM_URI, SIM_URI, FAKE_URI]))
    return graph(publishers, {}, uris, {})


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(looks(), NAMES, URIS), min_size=1, max_size=6))
def test_may_connect_is_exactly_trusted_uri_or_unguarded_topic(steps):
    policy = recorded()
    for look, topic, uri in steps:
        guarded_before = set(policy.guarded_topics)
        allowed = policy.may_connect(topic, uri, look)
        guarded = topic in policy.guarded_topics
        assert allowed == (not guarded or uri in (SIM_URI, CHECK_URI))
        assert guarded_before <= set(policy.guarded_topics), "the guard only grows"
        assert not set(policy.guarded_topics) & SHARED_TOPICS


@settings(max_examples=200, deadline=None)
@given(st.lists(looks(), min_size=1, max_size=6))
def test_violations_only_accumulate_each_once_and_a_stolen_name_teaches_nothing(seq):
    policy = recorded()
    seen = []
    for look in seq:
        guarded_before = set(policy.guarded_topics)
        new = policy.observe(look)
        assert policy.violations == seen + new
        seen = policy.violations
        assert len(seen) == len(set(seen))
        if look.node_uris["/turtlesim"] != SIM_URI:
            assert set(policy.guarded_topics) == guarded_before
            assert any("took the name /turtlesim" in v for v in seen)
        else:
            published = {t for t, nodes in look.publishers.items() if "/turtlesim" in nodes} - SHARED_TOPICS
            assert published <= set(policy.guarded_topics)
    for sentence in seen:
        assert "turtlesim" in sentence


@settings(max_examples=100, deadline=None)
@given(st.sampled_from(TURTLESIM_SERVICES + ("/turtle1/patrol", "/draw_arch")),
       st.sampled_from([SIM_SRV, FAKE_SRV]), st.sampled_from(["/turtlesim", "/fake"]))
def test_may_call_is_exactly_trusted_endpoint_or_unguarded_service(service, endpoint, provider):
    policy = recorded()
    look = turtlesim_graph(extra_providers={service: {provider}}, node_uris={"/fake": FAKE_URI},
                           service_uris={service: endpoint})
    allowed = policy.may_call(service, endpoint, look)
    assert allowed == (endpoint == SIM_SRV or service not in TURTLESIM_SERVICES)
    assert bool(policy.violations) == (not allowed)


def test_two_simulators_keep_their_own_labels():
    sim = Simulator("/sim", "the simulator (sim)", topics=("/odom",))
    policy = TrustPolicy([TURTLESIM, sim])
    look = turtlesim_graph({"/odom": {"/sim"}}, extra_providers={"/sim/get_loggers": {"/sim"}},
                           node_uris={"/sim": "http://localhost:40009/"},
                           service_uris={"/sim/get_loggers": "rosrpc://localhost:40010"})
    policy.record(look)
    assert not policy.may_connect("/odom", FAKE_URI, look)
    assert "which only the simulator (sim) may publish" in policy.violations[0]
