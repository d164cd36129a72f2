"""A course as data: read and check `courses/NAME/course.yaml` (docs/course_format.md).

A TA writes this file, so every mistake in it is reported where it is, as
`FILE:LINE: FIELD: what is wrong`, never as a traceback; all of a file's errors are reported at
once. A milestone is either data (`steps`, primitives of course_format.schema, run by the
generic check node `run_steps`) or a Python check (`check: NAME.test`). No ROS import: the
grader's command line reads this before any master runs.
"""
from __future__ import annotations

import json
import os
import re
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Tuple
from xml.sax.saxutils import quoteattr

import yaml

from course_format.milestone import Equivalent, Milestone, Step
from course_format import json_schema, saved, schema

COURSE_FILE = "course.yaml"
BUILTIN = "robotics_labs"
MILESTONE_ID = re.compile(r"^[a-z][a-z0-9_]*$")
PACKAGE_NAME = re.compile(r"^[a-z][a-z0-9_]*$")
TYPE_NAME = re.compile(r"^[A-Za-z]\w*/[A-Za-z]\w*$")
CHECK_FILE = re.compile(r"^[^./][^/]*\.test$")  # NAME.test, in the course's checks/
COMMAND = re.compile(r"^\s*%s\s+\S+\s*$" % PACKAGE_NAME.pattern.strip("^$"))  # start's 'PKG SCRIPT', 'PKG FILE.launch'
COURSE_KEYS = ("name", "title", "solution", "samples", "starter", "milestones")
MILESTONE_KEYS = ("id", "title", "text", "points", "packages", "world", "time_limit", "steps", "check",
                  "equivalent")
MUTANT_NAME = re.compile(r"^[a-z][a-z0-9_]*_[1-9][0-9]*$")  # course-lint's OPERATOR_N
DEFAULT_TIME_LIMIT_S = 90.0
DEFAULT_POINTS = 10.0

Path = Tuple[Any, ...]


class CourseError(ValueError):
    """A course file that cannot be used: every problem, each `FILE:LINE: FIELD: message`."""

    def __init__(self, problems: Sequence[str]) -> None:
        super().__init__("\n".join(problems))
        self.problems = list(problems)


class Course(NamedTuple):
    name: str
    title: str
    root: str  # the course folder
    file: str  # its course.yaml
    solution: Optional[str]  # the reference solution's folder, None when the course has none here
    samples: Optional[str]
    milestones: List[Milestone]
    starter: Optional[str] = None  # the code the texts hand out (similarity's boilerplate), if any

    def by_name(self) -> Dict[str, Milestone]:
        return {m.name: m for m in self.milestones}


def field_name(path: Path) -> str:
    """('milestones', 1, 'steps', 0, 'start') -> 'milestones[1].steps[0].start'."""
    out = ""
    for part in path:
        out += "[%d]" % part if isinstance(part, int) else ("." if out else "") + str(part)
    return out or "(the file)"


class _Lines:
    """The line of each field of the YAML document (1-based), from its node tree."""

    def __init__(self, root: Optional[yaml.Node]) -> None:
        self.root = root

    def of(self, path: Path) -> int:
        """The line of the field at `path`, or of its deepest ancestor the file has."""
        node = self.root
        if node is None:
            return 1
        line = node.start_mark.line + 1
        for part in path:
            child = None
            if isinstance(node, yaml.MappingNode):
                for key, value in node.value:
                    if isinstance(key, yaml.ScalarNode) and key.value == str(part):
                        child, line = value, key.start_mark.line + 1
                        break
            elif isinstance(node, yaml.SequenceNode) and isinstance(part, int) and 0 <= part < len(node.value):
                child = node.value[part]
                line = child.start_mark.line + 1
            if child is None:
                break
            node = child
        return line


class _Checker:
    """Collects the problems of one course file, each with its line."""

    def __init__(self, shown: str, lines: _Lines) -> None:
        self.shown = shown
        self.lines = lines
        self.problems: List[str] = []
        self.wrong: List[Tuple[int, Path]] = []  # the line and the path of each problem

    def error(self, path: Path, message: str) -> None:
        line = self.lines.of(path)
        problem = "%s:%d: %s: %s" % (self.shown, line, field_name(path), message)
        if problem not in self.problems:  # the schema and a check of the loader may both see it
            self.problems.append(problem)
            self.wrong.append((line, tuple(path)))

    def clean(self, path: Path) -> bool:
        """Whether no problem was found at `path` or inside it."""
        return not any(wrong[:len(path)] == tuple(path) for _, wrong in self.wrong)

    def in_order(self) -> List[str]:
        """The problems by line (those of one line in the order found)."""
        return [p for _, p in sorted(zip(self.wrong, self.problems), key=lambda pair: pair[0][0])]


def _is(value: Any, kind: str) -> bool:
    """Whether `value` is of the schema kind `kind` (told nothing: the JSON Schema says what is wrong)."""
    return {
        schema.STR: isinstance(value, str),
        schema.NUMBER: isinstance(value, (int, float)) and not isinstance(value, bool),
        schema.INT: isinstance(value, int) and not isinstance(value, bool),
        schema.BOOL: isinstance(value, bool),
        schema.LIST: isinstance(value, list),
        schema.MAP: isinstance(value, dict),
        schema.ANY: True,
    }[kind]


def _close(a: str, b: str) -> bool:
    """Whether `a` looks like a misspelling of `b`."""
    if a == b:
        return False
    if a.replace("-", "_").lower() == b:
        return True
    if abs(len(a) - len(b)) > 2:
        return False
    previous = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        current = [i]
        for j, cb in enumerate(b, 1):
            current.append(min(previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (ca != cb)))
        previous = current
    return previous[-1] <= 2


def load(path: str) -> Course:
    """The course in `path` (a course folder or its course.yaml). CourseError when it cannot be used."""
    file = os.path.join(path, COURSE_FILE) if os.path.isdir(path) else path
    file = os.path.abspath(file)
    shown = os.path.relpath(file) if not os.path.relpath(file).startswith("../..") else file
    try:
        with open(file, encoding="utf-8") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as err:
        raise CourseError(["%s:1: (the file): cannot be read: %s" % (shown, err)]) from None
    return parse(text, file, shown)


def parse(text: str, file: str, shown: str = "") -> Course:
    """The course whose course.yaml `file` holds `text`."""
    shown = shown or file
    try:
        data = yaml.safe_load(text)
        node = yaml.compose(text)
    except yaml.YAMLError as err:
        mark = getattr(err, "problem_mark", None)
        raise CourseError(["%s:%d: (the file): not YAML: %s" % (
            shown, mark.line + 1 if mark else 1, getattr(err, "problem", None) or err)]) from None
    check = _Checker(shown, _Lines(node))
    root = os.path.dirname(file)
    for where, message in json_schema.problems(data):  # keys, kinds, names and ranges: the JSON Schema's
        check.error(where, message)
    if not isinstance(data, dict):
        raise CourseError(check.problems)
    folders = {}
    for key in ("solution", "samples", "starter"):
        if _is(data.get(key), schema.STR):
            folder = os.path.normpath(os.path.join(root, data[key]))
            folders[key] = folder if os.path.isdir(folder) else None
    milestones: List[Milestone] = []
    raw = data.get("milestones")
    if isinstance(raw, list):  # what the schema cannot say: ids that differ, files that exist, steps' relations
        seen: Dict[str, int] = {}
        for i, item in enumerate(raw):
            m = _milestone(check, ("milestones", i), item, root, file)
            if m is None:
                continue
            if m.name in seen:
                check.error(("milestones", i, "id"), "%r is also milestones[%d]'s id" % (m.name, seen[m.name]))
            seen[m.name] = i
            milestones.append(m)
    if check.problems:
        raise CourseError(check.in_order())
    return Course(str(data["name"]), str(data["title"]), root, file, folders.get("solution"),
                  folders.get("samples"), milestones, folders.get("starter"))


def _milestone(check: _Checker, path: Path, item: Any, root: str, file: str) -> Optional[Milestone]:
    """A milestone whose keys and values the JSON Schema has judged: what it cannot say (its check's
    file exists, its steps' relations), then the milestone, or None when anything in it is wrong."""
    if not isinstance(item, dict):
        return None
    test_file = ""
    steps: Tuple[Step, ...] = ()
    if _is(item.get("check"), schema.STR) and check.clean(path + ("check",)):
        test_file = _check_file(check, path + ("check",), item["check"], root)
    if _is(item.get("steps"), schema.LIST):
        steps = _steps(check, path + ("steps",), item["steps"], os.path.basename(file))
    equivalent = _equivalent(check, path + ("equivalent",), item.get("equivalent", {}), item.get("packages"))
    if not check.clean(path):
        return None
    points = item.get("points", DEFAULT_POINTS)
    limit = item.get("time_limit", DEFAULT_TIME_LIMIT_S)
    packages = item.get("packages", [])
    world = item.get("world", [])
    return Milestone(item["id"], item["title"], item["text"], test_file, tuple(packages), float(points),
                     steps, tuple(world), file, float(limit), equivalent)


def _equivalent(check: _Checker, path: Path, given: Any, packages: Any) -> Tuple[Equivalent, ...]:
    """`equivalent: {NAME: REASON}`: the mutants course-lint makes of this milestone's reference
    (NAME as it names them, OPERATOR_N) that no check can kill, each with the reason a reviewer
    reads. Whether each names a surviving mutant only course-lint can tell (docs/course_lint.md); the
    names' and reasons' form (MUTANT_NAME, some text) is the JSON Schema's."""
    if not isinstance(given, dict):
        return ()
    if given and not packages:
        check.error(path, "the milestone names no package: course-lint makes no mutant of it")
    return tuple(Equivalent(name, reason.strip(), check.lines.of(path + (name,)))
                 for name, reason in given.items() if isinstance(reason, str))


def _check_file(check: _Checker, path: Path, name: str, root: str) -> str:
    """The rostest file of a Python check: the course's own checks/NAME (a course keeps its checks in
    its folder, the built-in course as any other; its name's form is the JSON Schema's, CHECK_FILE)."""
    own = os.path.join(root, "checks", name)
    if os.path.isfile(own):
        return own
    check.error(path, "%r: no such file in %s" % (name, os.path.join(root, "checks")))
    return ""


def _steps(check: _Checker, path: Path, items: List[Any], shown: str) -> Tuple[Step, ...]:
    steps: List[Step] = []
    names: List[str] = []  # what start steps make known, for later steps' `node`
    kept: List[str] = []  # what steps saved (`call`'s save), for later steps' ${NAME}
    for i, item in enumerate(items):
        here = path + (i,)
        if not isinstance(item, dict) or len(item) != 1:  # what is wrong with it: the JSON Schema's
            continue
        (name, params), = item.items()
        primitive = schema.PRIMITIVES.get(name)
        params = {} if params is None else params
        if primitive is None or not isinstance(params, dict):
            continue
        filled = _params(check, here + (name,), primitive, params, names)
        _references(check, here + (name,), filled, kept)
        if check.clean(here):
            where = "%s:%d (%s)" % (shown, check.lines.of(here), field_name(here))
            steps.append(Step(name, filled, where))
    return tuple(steps)


def _references(check: _Checker, path: Path, params: Dict[str, Any], kept: List[str]) -> None:
    """Every ${NAME} names a value a step before this one saved (a call's `expect`, also one this call
    saves); a call's `save` is NAME: FIELD, its names added to `kept` for the steps after it."""
    own = params.get("save") if isinstance(params.get("save"), dict) else {}  # its form: the JSON Schema's
    for key, value in params.items():
        if key == "save":
            continue
        known = kept + [k for k in own if isinstance(k, str)] if key == "expect" else kept
        for name in saved.references(value):
            if name not in known:
                close = [k for k in known if _close(name, k)]
                check.error(path + (key,), "${%s}: no step before this one saves a value of that name%s (saved: %s)"
                            % (name, " (did you mean %s?)" % close[0] if close else "", ", ".join(known) or "none"))
    kept.extend(k for k in own if isinstance(k, str) and k not in kept)


def _params(check: _Checker, path: Path, primitive: schema.Primitive, params: Dict[Any, Any],
            names: List[str]) -> Dict[str, Any]:
    """The step's parameters with their defaults; a value of another kind left out (the JSON Schema has
    said so), so that the checks below see only values of their kinds."""
    filled: Dict[str, Any] = {}
    for p in primitive.params:
        if p.name not in params:
            filled[p.name] = p.default
        elif _is(params[p.name], p.kind):
            filled[p.name] = params[p.name]
    _semantics(check, path, primitive.name, filled, names)
    return filled


def _semantics(check: _Checker, path: Path, name: str, params: Dict[str, Any], names: List[str]) -> None:
    """What the JSON Schema does not say: a start names one command, 'PKG SCRIPT', regular expressions
    compile, a `node` names a node started before, a predicate's bounds are in order, a layout's
    types are among those named, a drawing's shape takes its sizes."""
    if name == "start":  # one command, 'PKG SCRIPT' (COMMAND): the JSON Schema's; the name it makes known
        commands = [params[k] for k in ("rosrun", "roslaunch") if isinstance(params.get(k), str)]
        if len(commands) == 1 and COMMAND.match(commands[0]):
            names.append(params.get("as") or commands[0].split()[1])
    if isinstance(params.get("pattern"), str):
        _regex(check, path + ("pattern",), params["pattern"])
    node = params.get("node")
    if isinstance(node, str) and not node.startswith("/") and node not in names:
        check.error(path + ("node",), "%r: no start step before this one is named so (started: %s); a node "
                                      "name starts with /" % (node, ", ".join(names) or "none"))
    for key in ("fields", "expect"):
        value = params.get(key)
        if not isinstance(value, dict):
            continue
        if name == "param_is":
            _predicate(check, path + (key,), value)
            continue
        for field, predicate in value.items():
            _predicate(check, path + (key, field), predicate)
    layouts = params.get("layouts")
    if isinstance(layouts, dict):
        named = {k for k in (params.get("messages") or []) + (params.get("services") or []) if isinstance(k, str)}
        for kind, layout in layouts.items():
            if kind not in named:
                check.error(path + ("layouts", kind), "%r is not among the messages and services named" % (kind,))
            parts = [layout] if kind in (params.get("messages") or []) else [
                (layout or {}).get(k) for k in ("request", "response")] if isinstance(layout, dict) else [None]
            for part in parts:
                if not (isinstance(part, dict) and all(isinstance(k, str) and isinstance(v, str)
                                                       for k, v in part.items())):
                    check.error(path + ("layouts", kind), "expected {field: type} (a service: {request: {field: "
                                                          "type}, response: {field: type}}); got %r" % (layout,))
                    break
    if name in DRAWING_PARAMS:
        _drawing(check, path, name, params)
    if name in REST_STEPS:
        _rest(check, path, name, params)


# The drawing steps' parameters that a shape takes (the others it does not), and their ranges.
DRAWING_PARAMS = {"draws": ("radius", "angle", "side", "tolerance"), "in_bounds": ("for",),
                  "pen_colour": ("r", "g", "b", "tolerance")}
SHAPE_PARAMS = {"circle": ("radius",), "arc": ("angle", "radius"), "square": ("side",)}
MAY_BE_ZERO = ("for", "tolerance", "r", "g", "b")


def _drawing(check: _Checker, path: Path, name: str, params: Dict[str, Any]) -> None:
    """The drawing steps: a shape given only its own sizes (an arc its angle), a box not empty (the
    shapes, sizes, tolerances and colour channels are the JSON Schema's: SHAPE_PARAMS, RANGES)."""
    numbers = {k: v for k, v in params.items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
    if name == "draws" and params.get("shape") in SHAPE_PARAMS:
        shape = params["shape"]
        for key in ("radius", "angle", "side"):
            if params.get(key) is not None and key not in SHAPE_PARAMS[shape]:
                check.error(path + (key,), "a %s has no %s (it takes %s)" % (shape, key,
                                                                             ", ".join(SHAPE_PARAMS[shape])))
        if shape == "arc" and params.get("angle") is None:
            check.error(path, "an arc needs its angle: the angle turned, rad")
    for low, high in (("xmin", "xmax"), ("ymin", "ymax")):
        if name == "in_bounds" and low in numbers and high in numbers and numbers[low] >= numbers[high]:
            check.error(path + (high,), "%s %r is not above %s %r: the box is empty" % (high, numbers[high], low,
                                                                                       numbers[low]))


# The steps that judge a turtle at rest, and their parameters that are 0 or more (`still`: above 0).
REST_STEPS = {"stops_at": ("tolerance", "heading_tolerance", "still", "within"),
              "turns": ("tolerance", "drift", "still", "within")}
# Each bounded step parameter's range in JSON Schema's words, which the loader checks through the
# schema (course_format.json_schema): (step, parameter) -> {minimum|exclusiveMinimum|maximum|exclusiveMaximum: bound}.
RANGES: Dict[Tuple[str, str], Dict[str, float]] = {
    (name, key): {"minimum" if key in MAY_BE_ZERO else "exclusiveMinimum": 0}
    for name, keys in DRAWING_PARAMS.items() for key in keys}
RANGES[("draws", "tolerance")]["exclusiveMaximum"] = 1  # relative to the shape's sizes
for _channel in ("r", "g", "b"):
    RANGES[("pen_colour", _channel)]["maximum"] = 255
RANGES.update({(name, key): {"exclusiveMinimum" if key == "still" else "minimum": 0}
               for name, keys in REST_STEPS.items() for key in keys})


def _rest(check: _Checker, path: Path, name: str, params: Dict[str, Any]) -> None:
    """stops_at names a point (x and y), a heading, or both; turns an angle other than 0 (their
    tolerances are 0 or more, and `still` more than 0 s: RANGES, the JSON Schema's)."""
    numbers = {k: v for k, v in params.items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
    if name == "stops_at":
        if (params.get("x") is None) != (params.get("y") is None):
            check.error(path + ("y" if params.get("y") is None else "x",), "missing: a point is x and y")
        elif params.get("x") is None and params.get("heading") is None:
            check.error(path, "give the point it stops at (x, y), its heading, or both")
    if name == "turns" and numbers.get("angle") == 0:
        check.error(path + ("angle",), "0: a turn is by an angle other than 0 rad (left positive)")


def _regex(check: _Checker, path: Path, pattern: str) -> None:
    try:
        re.compile(pattern)
    except re.error as err:
        check.error(path, "%r is not a regular expression: %s" % (pattern, err))


def _predicate(check: _Checker, path: Path, predicate: Any) -> None:
    """What the JSON Schema does not say of a predicate (its keys and kinds it does): its regular
    expression compiles, its bounds are in order."""
    if not isinstance(predicate, dict):
        return
    if isinstance(predicate.get("matches"), str):
        _regex(check, path + ("matches",), predicate["matches"])
    bounds = predicate.get("between")
    if isinstance(bounds, list) and len(bounds) == 2 and all(_is(b, schema.NUMBER) for b in bounds) \
            and not bounds[0] <= bounds[1]:
        check.error(path + ("between",), "expected [LO, HI], two numbers, LO <= HI; got %r" % (bounds,))


DURATIONS_FILE = "durations.json"


def typical_durations(course: Course) -> Dict[str, float]:
    """The course's durations.json, if it has one: how long each milestone's run typically takes,
    in seconds (the order the first grading into a fresh output folder starts runs in, longest
    first). Only a hint: a missing or malformed file, or a value that is no positive number, is
    left out, and changes no verdict."""
    try:
        with open(os.path.join(course.root, DURATIONS_FILE)) as f:
            data = json.load(f)
    except (OSError, ValueError):
        return {}
    if not isinstance(data, dict):
        return {}
    return {str(k): float(v) for k, v in data.items()
            if isinstance(v, (int, float)) and not isinstance(v, bool) and 0 < v < float("inf")}


def builtin_course_dir() -> str:
    """The built-in course's folder (the five texts): courses/robotics_labs of this checkout."""
    here = os.path.dirname(os.path.abspath(__file__))
    while True:
        candidate = os.path.join(here, "courses", BUILTIN)
        if os.path.isfile(os.path.join(candidate, COURSE_FILE)):
            return candidate
        parent = os.path.dirname(here)
        if parent == here:
            raise CourseError(["courses/%s/%s: not found above %s" % (BUILTIN, COURSE_FILE, __file__)])
        here = parent


def milestone(course_yaml: str, milestone_id: str) -> Milestone:
    """One milestone of a course file (KeyError when it has none of that id)."""
    return load(course_yaml).by_name()[milestone_id]


def test_launch(m: Milestone, pkg: str = "") -> str:
    """The rostest file that runs a data milestone: its world's trusted nodes, then the generic check
    node `run_steps` reading the milestone from its course file."""
    lines = ['<?xml version="1.0"?>', "<!-- Milestone %s (%s), written by the grader from %s -->"
             % (m.name, m.text.replace("--", "- -"), m.course_file.replace("--", "- -")), "<launch>"]
    for world in m.world:
        package, kind = schema.WORLDS[world]
        lines.append("  <node pkg=%s type=%s name=%s/>" % (quoteattr(package), quoteattr(kind), quoteattr(world)))
    lines.append('  <test test-name=%s name="run_steps" pkg="course_milestones" type="run_steps" '
                 "time-limit=%s>" % (quoteattr(m.name), quoteattr("%g" % m.time_limit)))
    for key, value in (("course_file", m.course_file), ("milestone", m.name),
                       ("pkg", pkg or (m.packages[0] if m.packages else ""))):
        lines.append("    <param name=%s value=%s/>" % (quoteattr(key), quoteattr(value)))
    lines += ["  </test>", "</launch>", ""]
    return "\n".join(lines)
