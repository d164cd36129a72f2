"""What the page's graph, topic and plot panels ask the server, as JSON-ready dicts, and what the
page's header says in words about the ROS side (/api/health).

The page is told its node graph, its topic lists and the header's words on its websocket
(course_web.lab_status) and other clients GET them (/api/graph, /api/topics, /api/health); the page
turns an rqt_plot path (`/turtle1/pose/x:y`) into the fields to read with /api/plot, so the
browser never parses ROS types itself. The answers are built here from what the master says
(passed in: the real one, the cache of course_web.master_cache, or a fake in tests) with
course_introspection, the same model the rqt_graph and rqt_plot stand-ins use; the page then
subscribes through the rosbridge socket.
"""
from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Protocol, Sequence

from course_introspection.graph_model import GraphOptions, SystemState, build_graph
from course_introspection.plot_fields import PlotPathError, expand_shorthand, fields_of, parse_steps

Json = Dict[str, Any]
MAX_PLOT_SPEC = 2000
MAX_PLOT_FIELDS = 32
DEFAULT_CANVAS_TOPIC = "/turtlesim/scene"  # what the canvas panel draws from (www/index.html's default node + /scene)


class ApiError(ValueError):
    """A request the API cannot answer; `status` is the HTTP status to give."""

    def __init__(self, message: str, status: int = 400) -> None:
        super().__init__(message)
        self.status = status


class Master(Protocol):
    """The questions asked of the ROS master (rosgraph.Master answers them), and whether a node
    answers (its own XML-RPC server)."""

    def system_state(self) -> Sequence[Sequence]:
        """getSystemState(): [publishers, subscribers, services], each [name, [nodes]] rows."""

    def topic_types(self) -> Mapping[str, str]:
        """getTopicTypes() as topic -> type."""

    def node_answers(self, name: str) -> bool:
        """Whether the node `name` answers (it may be registered yet dead)."""


def graph(master: Master, show_debug: bool = False) -> Json:
    """The node/topic graph as rqt_graph's default view draws it (rosout hidden unless asked)."""
    state = SystemState.from_master(master.system_state())
    types = master.topic_types()
    built = build_graph(state, GraphOptions(hide_debug=not show_debug))
    return {
        "nodes": sorted(built.nodes),
        "topics": [{"name": name, "type": types.get(name, "")} for name in sorted(built.topics)],
        "edges": [{"from": a, "to": b} for a, b, _ in sorted(built.edges)],
    }


def topics(master: Master) -> Json:
    """Every topic the master knows, with its type, sorted by name."""
    return {"topics": [{"name": name, "type": kind} for name, kind in sorted(master.topic_types().items())]}


def plot_fields(master: Master, spec: Optional[str]) -> Json:
    """The numeric fields an rqt_plot argument names: topic, type, label, and the steps to read.

    `spec` is what a user types after rqt_plot: paths separated by spaces or commas, `x:y`
    shorthands, names relative to / (the page has no namespace)."""
    if spec is None:
        spec = ""
    if len(spec) > MAX_PLOT_SPEC:
        raise ApiError("a plot request of %d characters is too long (at most %d)" % (len(spec), MAX_PLOT_SPEC))
    try:
        paths = ["/" + path.lstrip("/") for path in expand_shorthand(spec.split())]
        if not paths:  # empty, blank, or only separators
            raise ApiError("give a field to plot, like /turtle1/pose/x:y")
        for path in paths:
            parse_steps(path)
        types = dict(master.topic_types())
        by_topic = fields_of(paths, types)
    except PlotPathError as err:
        raise ApiError(str(err))
    fields: List[Json] = []
    for topic, found in by_topic.items():
        for field in found:
            fields.append({"topic": topic, "type": types[topic], "label": field.label,
                           "steps": [[step.name, step.index] for step in field.steps]})
    if len(fields) > MAX_PLOT_FIELDS:
        raise ApiError("%s names %d numbers; plot at most %d at once" % (spec.strip(), len(fields), MAX_PLOT_FIELDS))
    return {"fields": fields}


def canvas_topic(name: Optional[str]) -> str:
    """The topic a health question is about, as a global name (empty: the canvas's default)."""
    return "/" + (name or DEFAULT_CANVAS_TOPIC).strip().lstrip("/")


def publishers_of(state: Sequence[Sequence], topic: str) -> List[str]:
    """The nodes a getSystemState answer has publishing `topic`, sorted."""
    return sorted(next((row[1] for row in state[0] if row[0] == topic), None) or [])


def health(master: Master, canvas_topic_name: Optional[str]) -> Json:
    """In words, what keeps the page from showing the lab: the master does not answer (the student
    stopped `roscore`), or nothing publishes the canvas's topic (turtlesim is not running).
    `state` is "ok", "no-master" or "no-publisher"; `says` is the sentence the page shows."""
    topic = canvas_topic(canvas_topic_name)
    try:
        registered = publishers_of(master.system_state(), topic)
    except ApiError as err:
        if err.status != 503:
            raise
        return {"state": "no-master", "topic": topic,
                "says": "%s%s. Start it again (roscore): the page follows it when it is back."
                        % (str(err)[:1].upper(), str(err)[1:].rstrip("."))}
    alive = [node for node in registered if master.node_answers(node)]
    if not alive:
        silent = " (%s is still registered, but does not answer)" % ", ".join(registered) if registered else ""
        return {"state": "no-publisher", "topic": topic,
                "says": "No node publishes %s%s: turtlesim is not running. Start it (rosrun turtlesim "
                        "turtlesim_node): the canvas comes back with it." % (topic, silent)}
    return {"state": "ok", "topic": topic, "says": "", "publishers": alive}
