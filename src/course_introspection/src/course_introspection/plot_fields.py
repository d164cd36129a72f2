"""rqt_plot's field paths: parse `/topic/field/sub[2]/x`, check them against the message type,
and read the numbers out of a message.

rqt_plot (Debian has none) takes paths that join a topic name and a field path; the topic is the
longest prefix that is an advertised topic. `/turtle1/pose/x:y` is short for `/turtle1/pose/x
/turtle1/pose/y`, and one argument may hold several paths separated by commas. A path that ends
at a message means its numeric fields, one at a fixed-size numeric array means each element.
Types come from roslib.message.get_message_class, so any built message works without imports.
"""
from __future__ import annotations

import re
from typing import Any, Dict, Iterable, List, Mapping, NamedTuple, Optional, Sequence, Tuple

NUMERIC_TYPES = frozenset({"int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64",
                           "float32", "float64", "bool", "char", "byte"})
TIME_TYPES = frozenset({"time", "duration"})
STEP_PATTERN = re.compile(r"^([A-Za-z][A-Za-z0-9_]*)(?:\[([0-9]+)\])?$")


class PlotPathError(ValueError):
    """A path that cannot be plotted; the message is one sentence for the user."""


class Step(NamedTuple):
    """One field of a path, with the array index that follows it (`position[0]`)."""
    name: str
    index: Optional[int] = None

    def __str__(self) -> str:
        return self.name if self.index is None else "%s[%d]" % (self.name, self.index)


class PlotField(NamedTuple):
    """A number to plot: a topic and the steps from its message down to the number."""
    topic: str
    steps: Tuple[Step, ...]

    @property
    def label(self) -> str:
        return "/".join([self.topic.rstrip("/")] + [str(step) for step in self.steps])


def expand_shorthand(arguments: Sequence[str]) -> List[str]:
    """rqt_plot's argument forms as plain paths: `/a/x,/b/y` (several paths in one argument) and
    `/a/x:y:z` (sibling fields of the first one)."""
    paths: List[str] = []
    for argument in arguments:
        for part in (p for p in argument.split(",") if p):
            first, *siblings = part.split(":")
            if siblings and "/" not in first:
                raise PlotPathError("%s must start with a topic and a field, like /turtle1/pose/x:y" % part)
            paths.append(first)
            parent = first[:first.rfind("/")]
            paths.extend("%s/%s" % (parent, name) for name in siblings if name)
    return paths


def parse_steps(field_path: str) -> Tuple[Step, ...]:
    """`pose/pose/position/x` or `position[0]` as steps (empty for the whole message)."""
    steps = []
    for text in (t for t in field_path.split("/") if t):
        match = STEP_PATTERN.match(text)
        if not match:
            raise PlotPathError("%r is not a field name (a name, optionally with an index like [0])" % text)
        steps.append(Step(match.group(1), None if match.group(2) is None else int(match.group(2))))
    return tuple(steps)


def split_topic(path: str, topics: Iterable[str]) -> Optional[Tuple[str, str]]:
    """(topic, field path) with the longest advertised topic that starts `path`, or None."""
    matches = [t for t in topics if path == t or path.startswith(t.rstrip("/") + "/")]
    if not matches:
        return None
    topic = max(matches, key=len)
    return topic, path[len(topic):].strip("/")


def parse_type(type_name: str) -> Tuple[str, bool, Optional[int]]:
    """`float64[36]` -> ('float64', True, 36); `string[]` -> ('string', True, None)."""
    import roslib.msgs
    return roslib.msgs.parse_type(type_name)


def message_class(type_name: str) -> Any:
    """The Python class of a message type, found the way rostopic does (no imports by name)."""
    import roslib.message
    cls = roslib.message.get_message_class(type_name)
    if cls is None:
        raise PlotPathError("message type %s is unknown here (is its package built and sourced?)" % type_name)
    return cls


def resolve(topic: str, type_name: str, field_path: str) -> List[PlotField]:
    """The numbers that `field_path` of a `type_name` message on `topic` stands for.

    Raises PlotPathError for a missing field, a non-numeric one (string), an index on a field that
    is no array, or an array of unknown size without an index."""
    steps = parse_steps(field_path)
    label = _path(topic, steps)
    current = type_name
    for position, step in enumerate(steps):
        base, is_array, _ = parse_type(current)
        parent = _path(topic, steps[:position])
        if is_array:
            raise PlotPathError("%s: %s is an array (%s): give an element, like %s[0]/%s"
                                % (label, parent, current, parent, step.name))
        if base in NUMERIC_TYPES | TIME_TYPES | {"string"}:
            raise PlotPathError("%s has no field %s: %s is %s" % (label, step.name, parent, current))
        cls = message_class(base)
        if step.name not in cls.__slots__:
            raise PlotPathError("%s has no field %s (%s has: %s)"
                                % (label, step.name, base, ", ".join(cls.__slots__)))
        current = cls._slot_types[cls.__slots__.index(step.name)]
        base, is_array, size = parse_type(current)
        if step.index is not None:
            if not is_array:
                raise PlotPathError("%s: %s is %s, not an array" % (label, step.name, current))
            if size is not None and step.index >= size:
                raise PlotPathError("%s: %s has only %d elements" % (label, step.name, size))
            current = base
    return _numbers_at(PlotField(topic, steps), current)


def fields_of(paths: Sequence[str], topics: Mapping[str, str]) -> Dict[str, List[PlotField]]:
    """Topic -> the fields to plot from it, in the order the paths were given, each once.
    `topics` maps each advertised topic to its type; a path on none of them is a PlotPathError."""
    by_topic: Dict[str, List[PlotField]] = {}
    for path in paths:
        split = split_topic(path, topics)
        if split is None:
            raise PlotPathError("topic %s does not exist (no node publishes it)" % path)
        topic, field_path = split
        fields = by_topic.setdefault(topic, [])
        fields.extend(f for f in resolve(topic, topics[topic], field_path) if f not in fields)
    return by_topic


def _path(topic: str, steps: Sequence[Step]) -> str:
    return PlotField(topic, tuple(steps)).label


def _numbers_at(field: PlotField, type_name: str) -> List[PlotField]:
    base, is_array, size = parse_type(type_name)
    numeric = base in NUMERIC_TYPES or base in TIME_TYPES
    if not is_array and numeric:
        return [field]
    if is_array and numeric and size is not None:
        last = field.steps[-1]
        return [PlotField(field.topic, field.steps[:-1] + (Step(last.name, i),)) for i in range(size)]
    if base == "string":
        what = "a list of strings" if is_array else "a string"
        raise PlotPathError("%s is not numeric (it is %s)" % (field.label, what))
    if is_array:
        kind = "a variable-size array" if size is None else "an array of messages"
        raise PlotPathError("%s is %s (%s): give an element, like %s[0]" % (field.label, kind, type_name, field.label))
    cls = message_class(base)
    scalars = [PlotField(field.topic, field.steps + (Step(name),))
               for name, slot in zip(cls.__slots__, cls._slot_types) if slot in NUMERIC_TYPES]
    if not scalars:
        raise PlotPathError("%s is not numeric (a %s message with no numeric fields of its own; "
                            "name one of its fields: %s)" % (field.label, base, ", ".join(cls.__slots__)))
    return scalars


def value_of(message: Any, steps: Sequence[Step]) -> Optional[float]:
    """The number at `steps` in `message`, or None when an index is past the end of this message's
    variable-size array."""
    value = message
    for step in steps:
        value = getattr(value, step.name)
        if step.index is not None:
            if step.index >= len(value):
                return None
            value = value[step.index]
    if hasattr(value, "to_sec"):
        return value.to_sec()
    return float(value)
