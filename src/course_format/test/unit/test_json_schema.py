"""course_format.json_schema: the JSON Schema a TA's editor reads (courses/course.schema.json) is what
the generator gives from the format's one list of primitives and keys, every course names it, and
it agrees with the loader: on every course under courses/, and on documents built from the
primitives' parameters, valid and mutated, the loader accepts exactly what the schema validates,
but where they differ by design (LOADER_ONLY, each with why)."""
import difflib
import glob
import json
import math
import os
import re
import tempfile

import jsonschema
import pytest
import yaml
from hypothesis import HealthCheck, given, settings, strategies as st

from course_format import course_file, json_schema, schema
from course_format.course_file import CourseError

COURSES = os.path.dirname(course_file.builtin_course_dir())
SCHEMA_FILE = os.path.join(COURSES, json_schema.FILE)
COURSE_FILES = sorted(glob.glob(os.path.join(COURSES, "*", course_file.COURSE_FILE)))

# What the loader refuses in a document the schema validates, and why a schema does not say it.
LOADER_ONLY = {
    "a regular expression that does not compile (JSON Schema checks no regular expression's syntax)":
        r"is not a regular expression",
    "a `node` that names no earlier start step (a relation between steps)":
        r"no start step before this one is named so",
    "a ${NAME} that names no value an earlier step saved (a relation between steps)":
        r"no step before this one saves a value",
    "two milestones of one id (uniqueItems compares whole milestones, not their ids)":
        r"is also milestones\[\d+\]'s id",
    "a Python check whose rostest file is not in the course's checks/ (the file system)":
        r"no such file in",
    "between's LO above its HI (a relation between two values)":
        r"LO <= HI; got",
    "a layout of a type the step does not name, or not {field: type} for a message or a service (a relation "
    "between parameters)":
        r"is not among the messages and services named|expected \{field: type\}",
    "a drawing's size its shape does not take, an arc without its angle (a relation between parameters)":
        r"a \w+ has no \w+ \(it takes|an arc needs its angle",
    "an empty box, xmin not below xmax (a relation between parameters)":
        r"the box is empty",
    "stops_at's x without y, neither a point nor a heading; a turn by 0 (relations between parameters)":
        r"missing: a point is x and y|give the point it stops at|a turn is by an angle other than 0",
    "equivalent mutants named in a milestone that names no package (a relation between keys)":
        r"the milestone names no package",
    "an integer written 2.0 (JSON Schema's integer includes 2.0; a count or a colour channel is an int)":
        r"expected an integer, got -?[0-9.e+]+$",
}
LOADER_ONLY_RE = re.compile("|".join("(?:%s)" % r for r in LOADER_ONLY.values()))


def kept_text():
    with open(SCHEMA_FILE, encoding="utf-8") as f:
        return f.read()


KEPT = json.loads(kept_text())
EDITOR = jsonschema.Draft7Validator(KEPT)  # the file, as an editor checks with it


def test_the_schema_in_the_repository_is_what_the_generator_gives():
    kept, made = kept_text(), json_schema.text()
    if kept != made:
        diff = "".join(list(difflib.unified_diff(kept.splitlines(True), made.splitlines(True), "kept", "generated"))[:40])
        pytest.fail("courses/%s is not what course_format gives now (a primitive, a parameter or a key changed): "
                    "run `%s` in a sourced workspace and commit the file\n%s"
                    % (json_schema.FILE, json_schema.REGENERATE, diff))


def test_the_schema_is_draft_7_and_names_every_primitive_parameter_and_key_with_its_kind():
    document = json.loads(kept_text())
    jsonschema.Draft7Validator.check_schema(document)
    assert document["$schema"] == json_schema.DRAFT
    steps = document["definitions"]["step"]["properties"]
    assert list(steps) == list(schema.PRIMITIVES)
    for name, primitive in schema.PRIMITIVES.items():
        params = steps[name]["properties"]
        assert list(params) == [p.name for p in primitive.params], name
        assert [params[p.name].get("type") for p in primitive.params] == [
            json_schema.TYPES.get(p.kind) for p in primitive.params], name
        assert steps[name].get("required", []) == [p.name for p in primitive.params if p.required], name
    milestone = document["definitions"]["milestone"]["properties"]
    assert list(document["properties"]) == list(course_file.COURSE_KEYS)
    assert list(milestone) == list(course_file.MILESTONE_KEYS)
    assert document["definitions"]["milestone"]["properties"]["world"]["items"]["enum"] == list(schema.WORLDS)
    assert list(document["definitions"]["predicate"]["properties"]) == list(schema.PREDICATE_KEYS)
    unsaid = [key for key, value in list(document["properties"].items()) + list(milestone.items())
              if not set(value) - {"description"}]
    assert not unsaid, ("course_file's keys %s have no schema: say what each takes in course_format/json_schema.py "
                        "(_course_keys, _milestone_keys), then run `%s`" % (unsaid, json_schema.REGENERATE))


@pytest.mark.parametrize("path", COURSE_FILES, ids=lambda p: os.path.basename(os.path.dirname(p)))
def test_every_course_names_the_schema_on_its_first_line_and_both_accept_it(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    assert text.splitlines()[0] == json_schema.MODELINE, "%s: its first line names the schema for editors" % path
    assert course_file.load(path).milestones
    assert not [e.message for e in EDITOR.iter_errors(yaml.safe_load(text))]


def test_there_are_courses_to_hold_to_the_schema():
    assert len(COURSE_FILES) >= 2 and os.path.join(COURSES, course_file.BUILTIN, course_file.COURSE_FILE) in COURSE_FILES


def test_the_command_writes_the_file(tmp_path):
    target = tmp_path / "schema.json"
    assert json_schema.main(["--write", str(target)]) == 0
    assert target.read_text(encoding="utf-8") == json_schema.text()


# -- documents from the schema, valid and mutated --------------------------------------------------

STRINGS = st.sampled_from(["/chatter", "talker", "std_msgs/String", "hello", "turtle1", "/turtle1/pose", "a b",
                           "(unclosed", "${first}", "", "x"]) | st.text(max_size=6)
ANY = st.recursive(st.none() | st.booleans() | st.integers(-5, 300) | st.floats(allow_nan=False) | STRINGS,
                   lambda inner: st.lists(inner, max_size=2) | st.dictionaries(STRINGS, inner, max_size=2),
                   max_leaves=4)
FIELDS = st.sampled_from(["data", "x", "linear.x", "sum", "name2"])
# A course folder whose checks/ holds the Python checks a generated milestone names, mostly.
CHECKS = ("chatter.test", "mine.test")
FOLDER = tempfile.mkdtemp(prefix="schema-course-")
os.makedirs(os.path.join(FOLDER, "checks"))
for _name in CHECKS:
    with open(os.path.join(FOLDER, "checks", _name), "w") as _f:
        _f.write("<launch/>")


def resolve(node):
    while "$ref" in node:
        node = KEPT["definitions"][node["$ref"].rsplit("/", 1)[1]]
    return node


def number(node, integer):
    """Numbers within the node's bounds: integers, and for a number floats too."""
    low = node.get("minimum", node.get("exclusiveMinimum", -50))
    high = node.get("maximum", node.get("exclusiveMaximum", 300))
    whole = st.integers(math.floor(low) + 1 if "exclusiveMinimum" in node else math.ceil(low),
                        math.ceil(high) - 1 if "exclusiveMaximum" in node else math.floor(high))
    if integer:
        return whole
    return whole | st.floats(low, high, exclude_min="exclusiveMinimum" in node,
                             exclude_max="exclusiveMaximum" in node)


def of_type(node, kind):
    if kind == "string":
        text = st.from_regex(node["pattern"], fullmatch=True).filter(lambda s: "\n" not in s) \
            if "pattern" in node else STRINGS
        return text.filter(lambda s: len(s) >= node.get("minLength", 0))
    if kind in ("number", "integer"):
        return number(node, kind == "integer")
    if kind == "boolean":
        return st.booleans()
    if kind == "null":  # a step with nothing after it, unless it needs one of its parameters (oneOf)
        return st.nothing() if "oneOf" in node else st.none()
    if kind == "array":
        items = instances(node.get("items", {}))
        return st.lists(items, min_size=node.get("minItems", 0), max_size=node.get("maxItems", 3))
    return mapping(node)


MADE = {}  # id(node) -> its strategy, made once


def instances(node):
    """Values `node` of the JSON Schema validates."""
    node = resolve(node)
    if id(node) not in MADE:
        kinds = node.get("type")
        MADE[id(node)] = st.sampled_from(node["enum"]) if "enum" in node else ANY if kinds is None else st.one_of(
            *[of_type(node, kind) for kind in ([kinds] if isinstance(kinds, str) else kinds)])
        if node.get("title") == "check":  # mostly one that is there
            MADE[id(node)] = st.integers(0, 4).flatmap(
                lambda n, named=MADE[id(node)]: st.sampled_from(CHECKS) if n else named)
    return MADE[id(node)]


@st.composite
def mapping(draw, node):
    properties = node.get("properties", {})
    alternatives = [set(a["required"]) for a in node.get("oneOf", ())]
    chosen = draw(st.sampled_from(alternatives)) if alternatives else set()
    others = set().union(*alternatives) - chosen if alternatives else set()
    if node.get("maxProperties") == 1:
        keys = {draw(st.sampled_from(sorted(chosen or properties)))}
    else:
        keys = set(node.get("required", ())) | chosen | {
            k for k in properties if k not in others and draw(st.booleans())}
        if not keys and node.get("minProperties") and properties:
            keys = {draw(st.sampled_from(sorted(properties)))}
        for key, needs in node.get("dependencies", {}).items():
            if key in keys:
                keys |= set(needs)
    out = {key: draw(instances(properties[key])) for key in sorted(keys)}
    extra = node.get("additionalProperties")
    if isinstance(extra, dict):
        names = instances(node["propertyNames"]) if "propertyNames" in node else FIELDS
        out.update(draw(st.dictionaries(names, instances(extra), min_size=node.get("minProperties", 0), max_size=2)))
    return out


DOCUMENTS = instances(KEPT)
WRONG = st.sampled_from([None, True, 0, -1, 1.5, 2.0, 300, "", "a b", "(unclosed", "std_msgs/String", "/x",
                         [], [1, 0], {}, {"equals": 1}, "talker"]) | ANY
BOGUS_KEYS = st.sampled_from(["bogus", "publishs", "tolerance", "approx", "node", "steps", "check", "type", "as"])


def paths(value, here=()):
    yield here
    if isinstance(value, dict):
        for key, item in value.items():
            yield from paths(item, here + (key,))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            yield from paths(item, here + (i,))


@st.composite
def mutated(draw):
    """A valid document with one to three things changed: a value replaced, a key taken out or added."""
    document = draw(DOCUMENTS)
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(list(paths(document))))
        if not path:
            continue
        parent = document
        for part in path[:-1]:
            parent = parent[part]
        how = draw(st.sampled_from(["replace", "remove", "add"]))
        if how == "replace":
            parent[path[-1]] = draw(WRONG)
        elif how == "remove" and isinstance(parent, dict):
            del parent[path[-1]]
        elif isinstance(parent[path[-1]], dict):
            parent[path[-1]][draw(BOGUS_KEYS)] = draw(WRONG)
    return document


def within(field, problems):
    """Whether a problem (`FILE:LINE: FIELD: message`) names `field` or a field inside it."""
    return field == "(the file)" or any(p.split(": ", 1)[1].startswith((field + ": ", field + ".", field + "["))
                                        for p in problems)


def agree(document):
    text = yaml.safe_dump(document, allow_unicode=True)
    data = yaml.safe_load(text)  # what the loader reads
    errors = list(EDITOR.iter_errors(data))
    try:
        course_file.parse(text, os.path.join(FOLDER, course_file.COURSE_FILE), "course.yaml")
        problems = []
    except CourseError as err:
        problems = err.problems
    if errors:
        assert problems, "the schema refuses what the loader takes: %s" % errors[0].message
        for error in errors:  # the loader names the field of each of the schema's errors, or one inside it
            field = course_file.field_name(tuple(error.absolute_path))
            assert within(field, problems), "the schema's %s: %s, not among the loader's %s" % (field, error.message,
                                                                                          problems)
    else:
        unexplained = [p for p in problems if not LOADER_ONLY_RE.search(p)]
        assert not unexplained, "the loader refuses what the schema validates, for no reason of LOADER_ONLY: %s" \
            % unexplained
    return not errors, not problems


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(DOCUMENTS)
def test_a_document_the_schema_validates_the_loader_takes_but_for_the_reasons_named(document):
    assert agree(document)[0]  # built valid


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(mutated())
def test_on_a_mutated_document_the_loader_and_the_schema_agree(document):
    agree(document)


# -- the loader's sentences for the schema's errors ------------------------------------------------

def problems(steps, extra=""):
    text = "name: x\ntitle: y\nmilestones:\n  - id: a\n    title: t\n    text: x\n%s    steps:\n" % extra + "".join(
        "      - %s\n" % step for step in steps)
    with pytest.raises(CourseError) as err:
        course_file.parse(text, os.path.join(COURSES, "x", "course.yaml"), "course.yaml")
    return err.value.problems


@pytest.mark.parametrize("step, said", [
    ("start: {rosrun: a b, roslaunch: a b.launch}", "steps[0].start: give one of rosrun: 'PKG SCRIPT' or roslaunch"),
    ("start:", "steps[0].start: give one of rosrun"),
    ("start: {rosrun: a b, find: {publish: /x}}", "start.find: one of {publishes: TOPIC}"),
    ("start: {rosrun: a b, args: [[1]]}", "start.args[0]: [1]: a command-line word is a string or a number"),
    ("start: {roslaunch: a}", "start.roslaunch: 'a': expected 'PKG FILE.launch'"),
    ("publishes:", "steps[0].publishes: expected a mapping, got None"),
    ("publishes: {topic: /x, count: 2.0}", "publishes.count: expected an integer, got 2.0"),
    ("publishes: {topic: /x, type: String}", "publishes.type: 'String': a type is PKG/Name"),
    ("publishes: {topic: 3, count: x}", "publishes.topic: expected a string, got 3"),
    ("publishes: {topic: /x, fields: {data: {approx: 1, tolerance: -1}}}",
     "fields.data.tolerance: -1: expected a number from 0"),
    ("publishes: {topic: /x, fields: {data: {tolerance: 1}}}", "fields.data.tolerance: a tolerance goes with approx"),
    ("publishes: {topic: /x, fields: {data: {}}}", "fields.data: expected a predicate, a mapping of equals"),
    ("param_is: {name: /p, expect: {betwen: [1, 2]}}", "expect.betwen: unknown field (did you mean between?)"),
    ("call: {service: /s, expect: {x: {between: [1]}}}", "expect.x.between: expected [LO, HI], two numbers"),
    ("{publishes: {topic: /x}, subscribes: {topic: /x}}", "steps[0]: a step is one primitive with its parameters"),
    ("draws: {shape: circle, cause: wrong_valu}", "draws.cause: 'wrong_valu' is no cause (did you mean wrong_value?)"),
    ("pen_colour: {r: 256, g: 0, b: 0}", "pen_colour.r: 256: expected a number up to 255"),
])
def test_a_schema_error_reads_as_the_loader_says_it(step, said):
    found = problems([step])
    assert any(said in p for p in found), found


def test_a_value_of_the_wrong_kind_is_told_its_kind_alone():
    assert problems(["draws: {shape: circle, radius: x, tolerance: [1]}"]) == [  # not also out of range
        "course.yaml:8: milestones[0].steps[0].draws.radius: expected a number, got 'x'",
        "course.yaml:8: milestones[0].steps[0].draws.tolerance: expected a number, got [1]"]
