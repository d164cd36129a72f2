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

from course_format import causes
from course_format.milestone import Equivalent, Milestone, Step
from course_format import saved, schema

COURSE_FILE = "course.yaml"
BUILTIN = "robotics_labs"
MILESTONE_ID = re.compile(r"^[a-z][a-z0-9_]*$")
PACKAGE_NAME = re.compile(r"^[a-z][a-z0-9_]*$")
TYPE_NAME = re.compile(r"^[A-Za-z]\w*/[A-Za-z]\w*$")
COURSE_KEYS = ("name", "title", "solution", "samples", "starter", "milestones")
MILESTONE_KEYS = ("id", "title", "text", "points", "packages", "world", "time_limit", "steps", "check",
                  "equivalent")
MUTANT_NAME = re.compile(r"^[a-z][a-z0-9_]*_[1-9][0-9]*$")  # course-lint's OPERATOR_N
DEFAULT_TIME_LIMIT_S = 90.0

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

    def error(self, path: Path, message: str) -> None:
        self.problems.append("%s:%d: %s: %s" % (self.shown, self.lines.of(path), field_name(path), message))

    def kind(self, path: Path, value: Any, kind: str) -> bool:
        """Whether `value` is of the schema kind `kind`; an error when not."""
        ok = {
            schema.STR: isinstance(value, str),
            schema.NUMBER: isinstance(value, (int, float)) and not isinstance(value, bool),
            schema.INT: isinstance(value, int) and not isinstance(value, bool),
            schema.BOOL: isinstance(value, bool),
            schema.LIST: isinstance(value, list),
            schema.MAP: isinstance(value, dict),
            schema.ANY: True,
        }[kind]
        if not ok:
            words = {schema.STR: "a string", schema.NUMBER: "a number", schema.INT: "an integer",
                     schema.BOOL: "true or false", schema.LIST: "a list", schema.MAP: "a mapping"}
            self.error(path, "expected %s, got %r" % (words[kind], value))
        return ok

    def unknown_keys(self, path: Path, given: Dict[Any, Any], known: Sequence[str]) -> None:
        for key in given:
            if key not in known:
                close = [k for k in known if _close(str(key), k)]
                self.error(path + (key,), "unknown field%s (known: %s)" % (
                    " (did you mean %s?)" % close[0] if close else "", ", ".join(known)))


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
    if not isinstance(data, dict):
        check.error((), "expected a mapping with name, title and milestones")
        raise CourseError(check.problems)
    check.unknown_keys((), data, COURSE_KEYS)
    for key in ("name", "title"):
        if key not in data:
            check.error((key,), "missing")
        else:
            check.kind((key,), data[key], schema.STR)
    folders = {}
    for key in ("solution", "samples", "starter"):
        if key in data and check.kind((key,), data[key], schema.STR):
            folder = os.path.normpath(os.path.join(root, data[key]))
            folders[key] = folder if os.path.isdir(folder) else None
    milestones: List[Milestone] = []
    raw = data.get("milestones")
    if raw is None:
        check.error(("milestones",), "missing")
    elif check.kind(("milestones",), raw, schema.LIST):
        seen: Dict[str, int] = {}
        for i, item in enumerate(raw):
            m = _milestone(check, ("milestones", i), item, root, file)
            if m is None:
                continue
            if m.name in seen:
                check.error(("milestones", i, "id"), "%r is also milestones[%d]'s id" % (m.name, seen[m.name]))
            seen[m.name] = i
            milestones.append(m)
        if not raw:
            check.error(("milestones",), "no milestone")
    if check.problems:
        raise CourseError(check.problems)
    return Course(str(data["name"]), str(data["title"]), root, file, folders.get("solution"),
                  folders.get("samples"), milestones, folders.get("starter"))


def _milestone(check: _Checker, path: Path, item: Any, root: str, file: str) -> Optional[Milestone]:
    if not check.kind(path, item, schema.MAP):
        return None
    before = len(check.problems)
    check.unknown_keys(path, item, MILESTONE_KEYS)
    for key in ("id", "title", "text"):
        if key not in item:
            check.error(path + (key,), "missing")
        elif check.kind(path + (key,), item[key], schema.STR) and key == "id" and not MILESTONE_ID.match(item[key]):
            check.error(path + (key,), "%r: an id is lower case letters, digits and _, a letter first" % item[key])
    points = item.get("points", 10.0)
    if check.kind(path + ("points",), points, schema.NUMBER) and points < 0:
        check.error(path + ("points",), "negative")
    limit = item.get("time_limit", DEFAULT_TIME_LIMIT_S)
    if check.kind(path + ("time_limit",), limit, schema.NUMBER) and limit <= 0:
        check.error(path + ("time_limit",), "must be more than 0 s")
    packages = item.get("packages", [])
    if check.kind(path + ("packages",), packages, schema.LIST):
        for j, name in enumerate(packages):
            if not isinstance(name, str) or not PACKAGE_NAME.match(name):
                check.error(path + ("packages", j), "%r is not a catkin package name" % (name,))
    world = item.get("world", [])
    if check.kind(path + ("world",), world, schema.LIST):
        for j, name in enumerate(world):
            if not isinstance(name, str) or name not in schema.WORLDS:
                check.error(path + ("world", j), "%r: no such world (known: %s)" % (name, ", ".join(schema.WORLDS)))
    test_file = ""
    steps: Tuple[Step, ...] = ()
    if ("steps" in item) == ("check" in item):
        check.error(path, "give either steps (data) or check (a Python check's rostest file), not %s"
                    % ("both" if "steps" in item else "neither"))
    elif "check" in item:
        if check.kind(path + ("check",), item["check"], schema.STR):
            test_file = _check_file(check, path + ("check",), item["check"], root)
    elif check.kind(path + ("steps",), item["steps"], schema.LIST):
        steps = _steps(check, path + ("steps",), item["steps"], os.path.basename(file))
    equivalent = _equivalent(check, path + ("equivalent",), item.get("equivalent", {}), item.get("packages"))
    if len(check.problems) > before:
        return None
    return Milestone(item["id"], item["title"], item["text"], test_file, tuple(packages), float(points),
                     steps, tuple(world), file, float(limit), equivalent)


def _equivalent(check: _Checker, path: Path, given: Any, packages: Any) -> Tuple[Equivalent, ...]:
    """`equivalent: {NAME: REASON}`: the mutants course-lint makes of this milestone's reference
    (NAME as it names them, OPERATOR_N) that no check can kill, each with the reason a reviewer
    reads. Whether each names a surviving mutant only course-lint can tell (docs/course_lint.md)."""
    if not isinstance(given, dict):
        check.error(path, "expected a mapping of mutant names to reasons, e.g. {rate_div10_1: \"section 2 "
                          "fixes no rate\"}, got %r" % (given,))
        return ()
    if given and not packages:
        check.error(path, "the milestone names no package: course-lint makes no mutant of it")
    found = []
    for name, reason in given.items():
        if not isinstance(name, str) or not MUTANT_NAME.match(name):
            check.error(path + (name,), "%r: name a mutant as course-lint does, OPERATOR_N (e.g. rate_div10_1)"
                        % (name,))
        elif not isinstance(reason, str) or not reason.strip():
            check.error(path + (name,), "expected the reason a reviewer reads (why no check can kill it), got %r"
                        % (reason,))
        else:
            found.append(Equivalent(name, reason.strip(), check.lines.of(path + (name,))))
    return tuple(found)


def _check_file(check: _Checker, path: Path, name: str, root: str) -> str:
    """The rostest file of a Python check: the course's own checks/NAME (a course keeps its checks in
    its folder, the built-in course as any other)."""
    if not name.endswith(".test") or "/" in name or name.startswith("."):
        check.error(path, "%r: name a rostest file, NAME.test, in the course's checks/ folder" % name)
        return ""
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
        if not isinstance(item, dict) or len(item) != 1:
            check.error(here, "a step is one primitive with its parameters, e.g. {publishes: {topic: /chatter}} "
                              "(known: %s)" % ", ".join(schema.PRIMITIVES))
            continue
        (name, params), = item.items()
        primitive = schema.PRIMITIVES.get(name)
        if primitive is None:
            close = [k for k in schema.PRIMITIVES if _close(str(name), k)]
            check.error(here + (name,), "no such primitive%s (known: %s)" % (
                " (did you mean %s?)" % close[0] if close else "", ", ".join(schema.PRIMITIVES)))
            continue
        params = {} if params is None else params
        if not check.kind(here + (name,), params, schema.MAP):
            continue
        before = len(check.problems)
        filled = _params(check, here + (name,), primitive, params, names)
        _references(check, here + (name,), filled, kept)
        if len(check.problems) == before:
            where = "%s:%d (%s)" % (shown, check.lines.of(here), field_name(here))
            steps.append(Step(name, filled, where))
    return tuple(steps)


def _references(check: _Checker, path: Path, params: Dict[str, Any], kept: List[str]) -> None:
    """Every ${NAME} names a value a step before this one saved (a call's `expect`, also one this call
    saves); a call's `save` is NAME: FIELD, its names added to `kept` for the steps after it."""
    own = params.get("save") if isinstance(params.get("save"), dict) else {}
    for key, value in own.items():
        if not isinstance(key, str) or not saved.NAME.fullmatch(key):
            check.error(path + ("save", key), "%r: a saved value's name is letters, digits and _, not a digit first"
                        % (key,))
        elif not isinstance(value, str) or not value:
            check.error(path + ("save", key), "expected the answer's field (name2, pose.x), got %r" % (value,))
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
    known = [p.name for p in primitive.params]
    check.unknown_keys(path, params, known)
    filled: Dict[str, Any] = {}
    for p in primitive.params:
        if p.name not in params:
            if p.required:
                check.error(path + (p.name,), "missing (%s)" % (p.doc or p.kind))
            filled[p.name] = p.default
            continue
        value = params[p.name]
        if check.kind(path + (p.name,), value, p.kind):
            filled[p.name] = value
    _semantics(check, path, primitive.name, filled, names)
    return filled


def _semantics(check: _Checker, path: Path, name: str, params: Dict[str, Any], names: List[str]) -> None:
    """What the kinds alone do not say: a start names one command, regular expressions compile,
    predicates use known words, a `node` names a node started before."""
    if name == "start":
        commands = [k for k in ("rosrun", "roslaunch") if isinstance(params.get(k), str)]
        if len(commands) != 1:
            check.error(path, "give one of rosrun: 'PKG SCRIPT' or roslaunch: 'PKG FILE.launch'")
        else:
            words = params[commands[0]].split()
            if len(words) != 2 or not PACKAGE_NAME.match(words[0]):
                check.error(path + (commands[0],), "%r: expected 'PKG %s'" % (
                    params[commands[0]], "SCRIPT" if commands[0] == "rosrun" else "FILE.launch"))
            else:
                names.append(params.get("as") or words[1])
        found = params.get("find")
        if isinstance(found, dict):
            if len(found) != 1 or next(iter(found)) not in ("publishes", "subscribes", "advertises", "node") \
                    or not isinstance(next(iter(found.values())), str):
                check.error(path + ("find",), "one of {publishes: TOPIC}, {subscribes: TOPIC}, "
                                              "{advertises: SERVICE}, {node: /NAME}")
        for word in params.get("args") or []:
            if not isinstance(word, (str, int, float)):
                check.error(path + ("args",), "%r: a command-line word is a string or a number" % (word,))
    if isinstance(params.get("pattern"), str):
        _regex(check, path + ("pattern",), params["pattern"])
    cause = params.get("cause")
    if isinstance(cause, str) and cause not in causes.BY_KEY:
        close = [k for k in causes.BY_KEY if _close(cause, k)]
        check.error(path + ("cause",), "%r is no cause%s (known: course_format/causes.py)" % (
            cause, " (did you mean %s?)" % close[0] if close else ""))
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
    kind = params.get("type")
    if isinstance(kind, str) and name != "type" and not TYPE_NAME.match(kind):
        check.error(path + ("type",), "%r: a type is PKG/Name" % kind)
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
    for key in ("messages", "services", "actions"):
        for j, kind in enumerate(params.get(key) or []):
            if not isinstance(kind, str) or not TYPE_NAME.match(kind):
                check.error(path + (key, j), "%r: a type is PKG/Name" % (kind,))
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
    """The drawing steps: a shape of steps.shapes.SHAPES given only its own sizes (an arc its angle),
    sizes and tolerances above 0, a box not empty, colour channels 0-255."""
    numbers = {k: v for k, v in params.items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
    for key in DRAWING_PARAMS[name]:
        value = numbers.get(key)
        if value is not None and (value < 0 or value == 0 and key not in MAY_BE_ZERO):
            check.error(path + (key,), "%r: expected a number %s 0" % (value, "from" if key in MAY_BE_ZERO
                                                                       else "above"))
    if name == "draws" and isinstance(params.get("shape"), str):
        shape = params["shape"]
        if shape not in SHAPE_PARAMS:
            check.error(path + ("shape",), "%r: a shape is one of %s" % (shape, ", ".join(SHAPE_PARAMS)))
            return
        for key in ("radius", "angle", "side"):
            if params.get(key) is not None and key not in SHAPE_PARAMS[shape]:
                check.error(path + (key,), "a %s has no %s (it takes %s)" % (shape, key,
                                                                             ", ".join(SHAPE_PARAMS[shape])))
        if shape == "arc" and params.get("angle") is None:
            check.error(path, "an arc needs its angle: the angle turned, rad")
        if "tolerance" in numbers and numbers["tolerance"] >= 1:
            check.error(path + ("tolerance",), "%r: a relative tolerance is below 1" % (numbers["tolerance"],))
    for low, high in (("xmin", "xmax"), ("ymin", "ymax")):
        if name == "in_bounds" and low in numbers and high in numbers and numbers[low] >= numbers[high]:
            check.error(path + (high,), "%s %r is not above %s %r: the box is empty" % (high, numbers[high], low,
                                                                                       numbers[low]))
    for key in ("r", "g", "b"):
        if name == "pen_colour" and key in numbers and numbers[key] > 255:
            check.error(path + (key,), "%r: a colour channel is 0-255" % (numbers[key],))


# The steps that judge a turtle at rest, and their parameters that are 0 or more (`still`: above 0).
REST_STEPS = {"stops_at": ("tolerance", "heading_tolerance", "still", "within"),
              "turns": ("tolerance", "drift", "still", "within")}


def _rest(check: _Checker, path: Path, name: str, params: Dict[str, Any]) -> None:
    """stops_at names a point (x and y), a heading, or both; turns an angle other than 0; their
    tolerances are 0 or more, and `still` more than 0 s."""
    numbers = {k: v for k, v in params.items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
    for key in REST_STEPS[name]:
        value = numbers.get(key)
        if value is not None and (value < 0 or value == 0 and key == "still"):
            check.error(path + (key,), "%r: expected a number %s 0" % (value, "above" if key == "still" else "from"))
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
    if not isinstance(predicate, dict) or not predicate:
        check.error(path, "expected a predicate: {equals: V}, {differs: V}, {approx: V, tolerance: T}, "
                          "{matches: REGEX}, {between: [LO, HI]} or {nonempty: true}; got %r" % (predicate,))
        return
    check.unknown_keys(path, predicate, schema.PREDICATE_KEYS)
    if "tolerance" in predicate and "approx" not in predicate:
        check.error(path + ("tolerance",), "a tolerance goes with approx")
    for key in ("approx", "tolerance"):
        if key in predicate:
            check.kind(path + (key,), predicate[key], schema.NUMBER)
    if "matches" in predicate and check.kind(path + ("matches",), predicate["matches"], schema.STR):
        _regex(check, path + ("matches",), predicate["matches"])
    if "between" in predicate:
        bounds = predicate["between"]
        if not (isinstance(bounds, list) and len(bounds) == 2 and all(
                isinstance(b, (int, float)) and not isinstance(b, bool) for b in bounds) and bounds[0] <= bounds[1]):
            check.error(path + ("between",), "expected [LO, HI], two numbers, LO <= HI; got %r" % (bounds,))
    if "nonempty" in predicate:
        check.kind(path + ("nonempty",), predicate["nonempty"], schema.BOOL)


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
