"""The node/topic graph of a running system, built from the master's registrations.

Plain Python: `SystemState` holds what rosgraph.Master.getSystemState() answers
(topic -> publishing nodes, topic -> subscribing nodes) and `build_graph` turns it
into vertices and edges under the views rqt_graph offers, plus a namespace filter:

- "all" (default): node -> topic for a publisher, topic -> node for a subscriber;
- active_only: as "all" but only topics with both a publisher and a subscriber;
- nodes_only: node -> node, one edge per topic connecting them (labelled with it);
- topics_only: topic -> topic through each node that subscribes one and publishes the other.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, FrozenSet, Iterable, List, Sequence, Set, Tuple

# Topics and nodes rqt_graph hides under "Debug" by default.
DEBUG_NODES = frozenset({"/rosout"})
DEBUG_TOPICS = frozenset({"/rosout", "/rosout_agg"})

Registrations = Dict[str, FrozenSet[str]]


@dataclass(frozen=True)
class SystemState:
    """Topic registrations: which nodes publish and which subscribe to each topic."""

    publishers: Registrations
    subscribers: Registrations

    @classmethod
    def from_master(cls, state: Sequence[Sequence]) -> "SystemState":
        """From getSystemState()'s [publishers, subscribers, services] lists of [name, [nodes]]."""
        def table(rows: Iterable[Sequence]) -> Registrations:
            return {str(name): frozenset(str(n) for n in nodes) for name, nodes in rows}
        return cls(publishers=table(state[0]), subscribers=table(state[1]))

    def nodes(self) -> Set[str]:
        return {n for table in (self.publishers, self.subscribers) for nodes in table.values() for n in nodes}

    def topics(self) -> Set[str]:
        return set(self.publishers) | set(self.subscribers)


@dataclass(frozen=True)
class GraphOptions:
    """Which view to draw and what to leave out."""

    nodes_only: bool = False
    topics_only: bool = False
    active_only: bool = False
    namespaces: Tuple[str, ...] = ()
    hide_debug: bool = True

    def __post_init__(self) -> None:
        if self.nodes_only and self.topics_only:
            raise ValueError("nodes_only and topics_only are different views; choose one")


Edge = Tuple[str, str, str]  # (from, to, label)


@dataclass
class Graph:
    """Vertices (ROS nodes, topics) and directed edges, ready for drawing."""

    nodes: Set[str] = field(default_factory=set)
    topics: Set[str] = field(default_factory=set)
    edges: Set[Edge] = field(default_factory=set)


def in_namespace(name: str, namespaces: Sequence[str]) -> bool:
    """True if name is one of the namespaces or lies under one (no namespaces: everything)."""
    if not namespaces:
        return True
    for ns in namespaces:
        ns = "/" + ns.strip("/")
        if ns == "/" or name == ns or name.startswith(ns + "/"):
            return True
    return False


def build_graph(state: SystemState, options: GraphOptions = GraphOptions()) -> Graph:
    """The graph of `state` under `options` (see the module docstring for the views)."""
    hidden_nodes = DEBUG_NODES if options.hide_debug else frozenset()
    hidden_topics = DEBUG_TOPICS if options.hide_debug else frozenset()

    def kept(table: Registrations, topic: str) -> Set[str]:
        return {n for n in table.get(topic, ()) if n not in hidden_nodes}

    nodes = {n for n in state.nodes() if n not in hidden_nodes and in_namespace(n, options.namespaces)}
    links: List[Tuple[str, Set[str], Set[str]]] = []  # (topic, publishers kept, subscribers kept)
    for topic in sorted(state.topics() - hidden_topics):
        all_pubs, all_subs = kept(state.publishers, topic), kept(state.subscribers, topic)
        if not (all_pubs or all_subs):
            continue  # only hidden nodes use it (e.g. rosout's own topics)
        pubs, subs = all_pubs & nodes, all_subs & nodes
        if not (pubs or subs or in_namespace(topic, options.namespaces)):
            continue  # outside the namespaces and not touching a kept node
        if options.active_only and not (pubs and subs):
            continue
        links.append((topic, pubs, subs))

    graph = Graph()
    if options.nodes_only:
        graph.nodes = set(nodes)
        for topic, pubs, subs in links:
            graph.edges |= {(p, s, topic) for p in pubs for s in subs}
    elif options.topics_only:
        graph.topics = {topic for topic, _, _ in links}
        for topic_in, _, subs in links:
            for topic_out, pubs, _ in links:
                graph.edges |= {(topic_in, topic_out, node) for node in subs & pubs if topic_in != topic_out}
    else:
        graph.topics = {topic for topic, _, _ in links}
        graph.nodes = set(nodes)
        for topic, pubs, subs in links:
            graph.edges |= {(p, topic, "") for p in pubs} | {(topic, s, "") for s in subs}
    return graph
