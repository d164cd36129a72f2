"""The primitives a course file's `steps:` may name, with the parameters each takes.

A step is a one-key mapping, `{primitive: {parameter: value, ...}}`. This module is the format's
one source of truth: the course file loader (course_format.course_file) validates every step
against it (an unknown primitive or parameter, a missing or mistyped value is an error naming the
file, the line and the field), and the check node (course_milestones.steps.run) implements each
primitive named here. No ROS import: it is read where no master runs.

Actions change the world (start the student's node, publish, call, type keys, set a parameter);
checks observe it and fail with a cause (course_format.causes). Steps run in order; the first
failing check ends the milestone with its finding.
"""
from __future__ import annotations

from typing import Any, Dict, NamedTuple, Tuple

# value kinds a parameter may take
STR, NUMBER, INT, BOOL, LIST, MAP, ANY = "str", "number", "int", "bool", "list", "map", "any"
# a predicate on a value (a message field, a parameter, a service response field):
# {equals: V} {differs: V} {approx: V, tolerance: T} {matches: REGEX} {between: [LO, HI]} {nonempty: true}
PREDICATE_KEYS = ("equals", "differs", "approx", "tolerance", "matches", "between", "nonempty")


class Param(NamedTuple):
    name: str
    kind: str
    required: bool = False
    default: Any = None
    doc: str = ""


class Primitive(NamedTuple):
    name: str
    action: bool  # an action changes the world; a check observes it and may fail
    params: Tuple[Param, ...]
    doc: str

    def param(self, name: str) -> Param:
        return {p.name: p for p in self.params}[name]


NODE = Param("node", STR, doc="the student's node: a `start` step's `as` name, or a node name (/mimic); "
                             "default: the node the last `start` step found")
WITHIN = Param("within", NUMBER, default=15.0, doc="seconds to wait for it")
TURTLE = Param("turtle", STR, default="turtle1", doc="a turtle of the course's turtlesim")
CANVAS_M = 11.088889  # turtlesim's canvas, m (turtlesim.constants.WORLD_SIZE)
STILL = Param("still", NUMBER, default=0.5, doc="seconds without moving or turning that count as at rest")

_PRIMITIVES = (
    Primitive("start", True, (
        Param("rosrun", STR, doc="the text's command after `rosrun`: 'PKG SCRIPT'"),
        Param("roslaunch", STR, doc="the text's command after `roslaunch`: 'PKG FILE.launch'"),
        Param("args", LIST, default=[], doc="more command-line words (e.g. turtle1, _rate:=5)"),
        Param("find", MAP, doc="what the started node must register when the text leaves the executable or "
                               "launch file open: {publishes|subscribes|advertises: NAME} or {node: /NAME}; the "
                               "text's name is tried first, then each other of the package's"),
        Param("as", STR, doc="the name later steps use for this node (default: the script's name)"),
        Param("within", NUMBER, default=25.0, doc="seconds for a started node to register"),
    ), "start the student's executable (rosrun) or launch file (roslaunch) in the sandbox"),
    Primitive("publishes", False, (
        Param("topic", STR, True), Param("type", STR, doc="the message type, pkg/Name"), NODE,
        Param("min_rate", NUMBER, doc="Hz, at least"), Param("max_rate", NUMBER, doc="Hz, at most"),
        Param("count", INT, default=2, doc="messages to receive"),
        Param("fields", MAP, default={}, doc="field path (data, linear.x) -> predicate; every message received "
                                             "must satisfy them"),
        WITHIN,
    ), "the student's node publishes on a topic, with a type, a rate and fields as given"),
    Primitive("subscribes", False, (Param("topic", STR, True), NODE, WITHIN),
              "the student's node subscribes to a topic"),
    Primitive("advertises", False, (Param("service", STR, True), Param("type", STR), NODE, WITHIN),
              "the student's node offers a service, of a type"),
    Primitive("call", True, (
        Param("service", STR, True),
        Param("request", MAP, default={}, doc="request field -> value"),
        Param("expect", MAP, default={}, doc="response field -> predicate"),
        Param("save", MAP, default={}, doc="NAME -> response field: the answer's value, which this step's "
                                           "`expect` and later steps name as ${NAME}"),
        WITHIN,
    ), "call a service (the student's) and check its answer"),
    Primitive("publish", True, (
        Param("topic", STR, True), Param("type", STR, True), Param("message", MAP, default={}),
        Param("rate", NUMBER, default=10.0), Param("duration", NUMBER, default=1.0),
    ), "publish a message for a while (e.g. cmd_vel to the student's node)"),
    Primitive("set_param", True, (Param("name", STR, True), Param("value", ANY, True)),
              "`rosparam set NAME VALUE`"),
    Primitive("param_is", False, (Param("name", STR, True), Param("expect", MAP, True, doc="a predicate"), WITHIN),
              "a parameter on the server has a value"),
    Primitive("prints", False, (
        NODE, Param("pattern", STR, True, doc="a regular expression a line of the node's output matches"),
        Param("within", NUMBER, default=10.0),
    ), "the node prints a line matching a pattern, after the last action"),
    Primitive("type", True, (NODE, Param("keys", STR, True, doc="typed one character at a time; <up>, <down>, "
                                                                 "<left>, <right>, <enter>, <space>, <esc> name keys"),
                             Param("pause", NUMBER, default=0.1, doc="seconds between two keys")),
              "type keys on the node's terminal"),
    Primitive("teleport", True, (
        Param("turtle", STR, default="turtle1"), Param("x", NUMBER, True), Param("y", NUMBER, True),
        Param("theta", NUMBER, default=0.0),
    ), "put a turtle of the course's turtlesim at a place"),
    Primitive("turtle_moves", False, (
        Param("turtle", STR, default="turtle1"),
        Param("direction", STR, default="any", doc="any, forward, backward, left (turns), right (turns)"),
        Param("min_distance", NUMBER, default=0.2, doc="m (or rad for a turn)"),
        Param("within", NUMBER, default=5.0),
    ), "a turtle moves, after the last action"),
    Primitive("running", False, (Param("nodes", LIST, True, doc="node names"), WITHIN),
              "nodes of these names are registered with the master"),
    Primitive("generated", False, (
        Param("messages", LIST, default=[], doc="pkg/Name"), Param("services", LIST, default=[]),
        Param("actions", LIST, default=[]),
        Param("layouts", MAP, default={}, doc="pkg/Name -> the fields the text gives it, {field: type}; a "
                                              "service's as {request: {...}, response: {...}} (order not compared)"),
    ), "the student's build generated these messages, services and actions (with the text's fields)"),
    Primitive("tf_frame", False, (Param("frame", STR, True), Param("parent", STR), WITHIN),
              "a TF frame exists (with a parent)"),
    Primitive("tf_follows", False, (
        Param("frame", STR, True), Param("target", STR, True),
        Param("distance", NUMBER, default=1.0, doc="m: how close it comes"), Param("within", NUMBER, default=30.0),
    ), "a TF frame comes within a distance of another"),
    Primitive("draws", False, (
        TURTLE,
        Param("shape", STR, True, doc="circle, arc or square (steps.shapes.SHAPES)"),
        Param("radius", NUMBER, doc="m: the circle's or arc's radius (default: any)"),
        Param("angle", NUMBER, doc="rad: the angle an arc turns, either way (an arc needs it)"),
        Param("side", NUMBER, doc="m: the square's side (default: any, four of one length)"),
        Param("tolerance", NUMBER, default=0.15, doc="relative: of the radius, angle, side and a quarter turn"),
        Param("within", NUMBER, default=20.0, doc="seconds for the shape to be complete"),
    ), "a turtle draws a circle, an arc or a square, judged on its poses since the last action"),
    Primitive("in_bounds", False, (
        TURTLE,
        Param("xmin", NUMBER, default=0.0, doc="m; the box's edge is outside it (a turtle clamped on the wall hit it)"),
        Param("xmax", NUMBER, default=CANVAS_M, doc="m (default: turtlesim's canvas)"),
        Param("ymin", NUMBER, default=0.0, doc="m"),
        Param("ymax", NUMBER, default=CANVAS_M, doc="m"),
        Param("for", NUMBER, default=5.0, doc="seconds from the last action during which every pose is inside"),
    ), "a turtle stays inside a box, from the last action on"),
    Primitive("pen_colour", False, (
        TURTLE,
        Param("r", INT, True, doc="0-255"), Param("g", INT, True, doc="0-255"), Param("b", INT, True, doc="0-255"),
        Param("tolerance", INT, default=10, doc="per channel"),
        Param("within", NUMBER, default=5.0, doc="seconds to see the colour"),
    ), "the turtle's pen draws this colour where it is (the course's turtlesim's /TURTLE/color_sensor)"),
    Primitive("stops_at", False, (
        TURTLE,
        Param("x", NUMBER, doc="m: the point it stops at (with y; default: any place)"),
        Param("y", NUMBER, doc="m"),
        Param("tolerance", NUMBER, default=0.1, doc="m: how far from (x, y) it may stop"),
        Param("heading", NUMBER, doc="rad: the heading it stops with (0 along x, pi/2 along y; default: any)"),
        Param("heading_tolerance", NUMBER, default=0.05, doc="rad"),
        STILL,
        Param("within", NUMBER, default=20.0, doc="seconds for it to move and come to rest; a turtle that does not "
                                                  "move is judged where it stands then"),
    ), "where a turtle comes to rest after the last action: its distance to a point, its heading"),
    Primitive("turns", False, (
        TURTLE,
        Param("angle", NUMBER, True, doc="rad: the heading's change, left (counter-clockwise) positive; past pi "
                                         "counts (summed pose by pose)"),
        Param("either_way", BOOL, default=False, doc="true: |angle| to the left or to the right"),
        Param("tolerance", NUMBER, default=0.05, doc="rad"),
        Param("drift", NUMBER, default=0.05, doc="m: how far its position may move while it turns (in place)"),
        STILL,
        Param("within", NUMBER, default=20.0, doc="seconds for it to turn and come to rest"),
    ), "a turtle turns in place by an angle, judged once it comes to rest after the last action"),
)
# Every check may name the cause its failure is grouped under (the class view's groups), when it
# fails at what it checks: `prints` after a `set_param` fails as param_ignored. A failure that says
# the node is gone or the course file is wrong keeps its own cause (steps.run.KEEPS_OWN_CAUSE).
CAUSE = Param("cause", STR, doc="the cause (course_format.causes) this check's failure is grouped under")
PRIMITIVES: Dict[str, Primitive] = {
    p.name: p if p.action else p._replace(params=p.params + (CAUSE,)) for p in _PRIMITIVES}

# The trusted nodes a milestone's `world:` may start before the student's (rostest <node> lines).
WORLDS: Dict[str, Tuple[str, str]] = {
    "turtlesim": ("turtlesim", "turtlesim_node"),
}
