"""Whom a milestone check believes: the policy, as plain data and decisions (no rospy here).

A check judges a student by what the simulator reports (turtlesim's /turtle1/pose and
/turtle1/color_sensor, Gazebo's /gazebo/model_states, ...) and by calling the simulator's
services (/turtle1/teleport_absolute, /spawn, /turtlesim/snapshot, /gazebo/...). The student's
nodes share the ROS master with the check, and the master believes anyone: a student's node may
publish /turtle1/pose too, register /turtle1/teleport_absolute (the master then hands the
check the student's service), or take the simulator's node name (the master then shuts the
real simulator down). So the check trusts nodes, not names:

- The *trusted* nodes are the simulators the rostest launched, each recorded by its XML-RPC URI
  (and the TCPROS endpoints of its services) before any student code runs. A URI names one
  process: a node that takes the simulator's name gets another URI, which is how a takeover shows.
- The *guarded* topics and services are those a trusted node publishes or offers, as seen at the
  record and at every later look at the master (a turtle spawned later brings its own). The
  guard only grows: once the master has shown that turtlesim publishes /turtle2/pose, nobody
  else may, even after a student's service registration has displaced turtlesim's in the master.
  `/rosout`, which every node publishes, is never guarded.
- The check may connect to a publisher of a guarded topic only at a trusted URI, and call a
  guarded service only at a trusted endpoint. Anything else is a *violation*: a sentence saying
  what the student's node did, which fails the milestone whatever else the check saw.

course_milestones.guard wires this policy into the check's rospy; a Graph is one look at the
master as that module takes it.
"""
from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Dict, FrozenSet, Iterable, List, Mapping, Optional, Sequence, Set, Tuple

# Topics every node publishes: a student's node publishing them is normal.
SHARED_TOPICS: FrozenSet[str] = frozenset({"/rosout"})


class TrustError(RuntimeError):
    """The trusted nodes could not be recorded (a simulator had not registered what it should)."""


@dataclass(frozen=True)
class Simulator:
    """A node the rostest launches and the check believes.

    node: its name as the master knows it ("/turtlesim").
    label: what to call it in a sentence to the student ("turtlesim").
    topics, services: what it must have registered before it is recorded, so that the names the
        check relies on are guarded from the first student process on (later ones are guarded as
        the master shows them)."""

    node: str
    label: str
    topics: Tuple[str, ...] = ()
    services: Tuple[str, ...] = ()


# The simulators of the course's rostests, as they register themselves.
TURTLESIM = Simulator(
    "/turtlesim", "turtlesim",
    topics=("/turtle1/pose", "/turtle1/color_sensor", "/turtlesim/image"),
    services=("/clear", "/reset", "/spawn", "/kill", "/turtle1/set_pen", "/turtle1/teleport_absolute",
              "/turtle1/teleport_relative", "/turtlesim/snapshot"))
GAZEBO = Simulator(
    "/gazebo", "the simulator (gazebo)",
    topics=("/clock", "/gazebo/model_states", "/gazebo/link_states"),
    services=("/gazebo/spawn_urdf_model", "/gazebo/spawn_sdf_model", "/gazebo/delete_model",
              "/gazebo/get_model_state", "/gazebo/set_model_state", "/gazebo/get_link_state",
              "/gazebo/get_world_properties", "/gazebo/pause_physics", "/gazebo/unpause_physics",
              "/gazebo/reset_world", "/gazebo/reset_simulation"))


@dataclass(frozen=True)
class Graph:
    """One look at the master.

    publishers, providers: topic -> names of the nodes publishing it; service -> names of the
        nodes offering it (getSystemState).
    node_uris: node name -> XML-RPC URI, for the nodes that were looked up (lookupNode); a name
        missing here was not looked up or is not registered.
    service_uris: service -> TCPROS endpoint (rosrpc://...), for the services looked up."""

    publishers: Mapping[str, FrozenSet[str]] = field(default_factory=dict)
    providers: Mapping[str, FrozenSet[str]] = field(default_factory=dict)
    node_uris: Mapping[str, str] = field(default_factory=dict)
    service_uris: Mapping[str, str] = field(default_factory=dict)

    @classmethod
    def from_system_state(cls, state: Sequence[Sequence], node_uris: Optional[Mapping[str, str]] = None,
                          service_uris: Optional[Mapping[str, str]] = None) -> "Graph":
        """From the master's getSystemState answer [publishers, subscribers, services], each a list
        of [name, [node, ...]]."""
        publishers, _subscribers, services = state
        return cls({name: frozenset(nodes) for name, nodes in publishers},
                   {name: frozenset(nodes) for name, nodes in services},
                   dict(node_uris or {}), dict(service_uris or {}))

    def offered_by(self, node: str) -> Set[str]:
        return {name for name, nodes in self.providers.items() if node in nodes}

    def published_by(self, node: str) -> Set[str]:
        return {name for name, nodes in self.publishers.items() if node in nodes}

    def name_of(self, uri: str, candidates: Iterable[str]) -> Optional[str]:
        """The node among `candidates` that the master says is at `uri`, if any."""
        return next((n for n in sorted(candidates) if self.node_uris.get(n) == uri), None)


# -- the sentences a student reads ------------------------------------------------------------------

def publisher_sentence(node: Optional[str], uri: str, topic: str, owner: str) -> str:
    who = "your node %s" % node if node else "a node of yours (at %s)" % uri
    return ("%s publishes %s, which only %s may publish: the check believes the simulator alone, so remove "
            "that publisher" % (who, topic, owner))


def provider_sentence(node: Optional[str], endpoint: str, service: str, owner: str) -> str:
    who = "your node %s" % node if node else "a node of yours (at %s)" % endpoint
    return ("%s offers the service %s, which only %s may offer: the check calls the simulator alone, so remove "
            "that service" % (who, service, owner))


def forged_provider_sentence(name: str, endpoint: str, service: str, owner: str) -> str:
    return ("a node of yours offers the service %s under %s's name %s (at %s), which only %s may offer: remove "
            "that service" % (service, owner, name, endpoint, owner))


def takeover_sentence(name: str, owner: str, uri: str) -> str:
    return ("a node of yours took the name %s, which is %s's (now at %s): ROS shuts a node down when another "
            "registers under its name, so give your node a name of its own" % (name, owner, uri))


def missing_sentence(missing: Sequence[str]) -> str:
    return ("the check could not record the simulator before your code ran (%s), so it cannot tell the "
            "simulator from a fake: this is a fault of the grading run, not of your code; ask for a re-run"
            % "; ".join(missing))


class TrustPolicy:
    """The trusted nodes, the guarded names, the decisions and the violations (thread-safe: rospy
    asks from its connection threads while the check's test thread looks)."""

    def __init__(self, simulators: Sequence[Simulator], shared_topics: Iterable[str] = SHARED_TOPICS) -> None:
        self.simulators: Dict[str, Simulator] = {s.node: s for s in simulators}
        self.shared_topics = frozenset(shared_topics)
        self._lock = threading.Lock()
        self.trusted_uris: Dict[str, str] = {}          # simulator name -> its XML-RPC URI
        self.trusted_endpoints: Dict[str, str] = {}     # rosrpc endpoint -> simulator name
        self.own_uri: Optional[str] = None               # the check's own node: its data is its own
        self.guarded_topics: Dict[str, str] = {}        # topic -> simulator name
        self.guarded_services: Dict[str, str] = {}      # service -> simulator name
        self.problem: Optional[str] = None              # set when the record could not be made
        self._violations: List[str] = []

    # -- recording, before any student code runs ----------------------------------------------------

    def missing(self, graph: Graph) -> List[str]:
        """What the simulators have not registered yet in `graph` (empty: ready to record)."""
        found = []
        for sim in self.simulators.values():
            if sim.node not in graph.node_uris:
                found.append("%s is not registered" % sim.node)
                continue
            topics = [t for t in sim.topics if t not in graph.published_by(sim.node)]
            services = [s for s in sim.services if s not in graph.offered_by(sim.node)]
            if topics or services:
                found.append("%s has not registered %s yet" % (sim.node, ", ".join(topics + services)))
            elif not any(graph.service_uris.get(s) for s in graph.offered_by(sim.node)):
                found.append("the services of %s were not looked up" % sim.node)
        return found

    def record(self, graph: Graph, own_uri: Optional[str] = None) -> None:
        """Trust the simulators as `graph` shows them: their URIs, their services' endpoints, and
        what they publish and offer. Raises TrustError (and keeps it as `problem`) when `graph`
        lacks something `missing` asks for."""
        missing = self.missing(graph)
        with self._lock:
            if missing:
                self.problem = missing_sentence(missing)
                raise TrustError(self.problem)
            self.own_uri = own_uri
            for name in self.simulators:
                self.trusted_uris[name] = graph.node_uris[name]
                for service in graph.offered_by(name):
                    if service in graph.service_uris:
                        self.trusted_endpoints.setdefault(graph.service_uris[service], name)
            self._learn(graph)

    def fail_record(self, missing: Sequence[str]) -> None:
        """The simulators never became ready: every verdict says so (see `missing_sentence`)."""
        with self._lock:
            self.problem = missing_sentence(missing)

    # -- looking at the master later ----------------------------------------------------------------

    def _genuine(self, name: str, graph: Graph) -> bool:
        """`name` is a trusted simulator and the master still has it at its recorded URI."""
        return name in self.trusted_uris and graph.node_uris.get(name) == self.trusted_uris[name]

    def _learn(self, graph: Graph) -> None:
        """Guard what the genuine simulators publish and offer in `graph` (lock held)."""
        for name in self.trusted_uris:
            if not self._genuine(name, graph):
                continue
            for topic in graph.published_by(name) - self.shared_topics:
                self.guarded_topics.setdefault(topic, name)
            for service in graph.offered_by(name):
                endpoint = graph.service_uris.get(service)
                if endpoint is None or endpoint in self.trusted_endpoints:
                    self.guarded_services.setdefault(service, name)

    def _add(self, sentence: str) -> bool:
        if sentence in self._violations:
            return False
        self._violations.append(sentence)
        return True

    def observe(self, graph: Graph) -> List[str]:
        """Learn the guarded names `graph` shows and find what breaks the policy in it: a trusted
        name at another URI, a node other than the simulator publishing a guarded topic or
        offering a guarded service (by name, and by endpoint for the services `graph` looked up).
        Returns the violations new in this look."""
        new: List[str] = []
        with self._lock:
            self._learn(graph)
            for name, uri in self.trusted_uris.items():
                now = graph.node_uris.get(name)
                if now is not None and now != uri:
                    sentence = takeover_sentence(name, self.simulators[name].label, now)
                    if self._add(sentence):
                        new.append(sentence)
            for topic, owner in self.guarded_topics.items():
                for node in sorted(graph.publishers.get(topic, ())):
                    if node in self.simulators:
                        continue  # the simulator itself; under a stolen name, the takeover says it
                    sentence = publisher_sentence(node, graph.node_uris.get(node, "?"), topic,
                                                  self.simulators[owner].label)
                    if self._add(sentence):
                        new.append(sentence)
            for service, owner in self.guarded_services.items():
                label = self.simulators[owner].label
                endpoint = graph.service_uris.get(service)
                for node in sorted(graph.providers.get(service, ())):
                    if node not in self.simulators:
                        sentence = provider_sentence(node, endpoint or "?", service, label)
                    elif endpoint is not None and endpoint not in self.trusted_endpoints:
                        sentence = forged_provider_sentence(node, endpoint, service, label)
                    else:
                        continue
                    if self._add(sentence):
                        new.append(sentence)
        return new

    # -- the decisions ------------------------------------------------------------------------------

    def trusts_uri(self, uri: str) -> bool:
        """`uri` is a recorded simulator's XML-RPC URI, or the check's own."""
        with self._lock:
            return uri == self.own_uri or uri in self.trusted_uris.values()

    def guarded_topic_names(self) -> List[str]:
        with self._lock:
            return sorted(self.guarded_topics)

    def guarded_service_names(self) -> List[str]:
        with self._lock:
            return sorted(self.guarded_services)

    def is_guarded_topic(self, topic: str) -> bool:
        with self._lock:
            return topic in self.guarded_topics

    def may_connect(self, topic: str, pub_uri: str, graph: Graph) -> bool:
        """May the check's subscriber to `topic` take data from the publisher at `pub_uri`? Yes
        from a trusted URI, or on a topic no simulator publishes; otherwise no, and the publisher
        (named from `graph` when the master knows it) is a violation."""
        with self._lock:
            self._learn(graph)
            owner = self.guarded_topics.get(topic)
            if owner is None or pub_uri == self.own_uri or pub_uri in self.trusted_uris.values():
                return True
            node = graph.name_of(pub_uri, graph.publishers.get(topic, ()))
            self._add(publisher_sentence(node, pub_uri, topic, self.simulators[owner].label))
            return False

    def may_call(self, service: str, endpoint: str, graph: Graph) -> bool:
        """May the check call `service` at `endpoint` (the master's lookupService answer)? Yes at a
        trusted endpoint, or when no simulator offers `service`; otherwise no, and the provider
        (named from `graph`) is a violation."""
        return self.call_refusal(service, endpoint, graph) is None

    def call_refusal(self, service: str, endpoint: str, graph: Graph) -> Optional[str]:
        """None when the check may call `service` at `endpoint` (see may_call), else the violation."""
        with self._lock:
            self._learn(graph)
            owner = self.guarded_services.get(service)
            if owner is None or endpoint in self.trusted_endpoints:
                return None
            label = self.simulators[owner].label
            nodes = sorted(graph.providers.get(service, ()))
            node = nodes[0] if nodes else None
            if node in self.simulators:
                sentence = forged_provider_sentence(node, endpoint, service, label)
            else:
                sentence = provider_sentence(node, endpoint, service, label)
            self._add(sentence)
            return sentence

    @property
    def violations(self) -> List[str]:
        """Every violation seen so far, first seen first, each once."""
        with self._lock:
            return list(self._violations)

    def verdict(self) -> List[str]:
        """What must fail the check: the record's problem, if any, then the violations."""
        with self._lock:
            return ([self.problem] if self.problem else []) + list(self._violations)
