"""course.yaml's JSON Schema: what a TA's editor completes and checks, made from the format itself.

One document (JSON Schema draft-07, what the YAML language server reads) is generated from the
format's one list of primitives (course_format.schema: PRIMITIVES, each parameter's kind, default
and doc, WORLDS, PREDICATE_KEYS), the course's and a milestone's keys (course_file.COURSE_KEYS,
MILESTONE_KEYS) and the loader's names, patterns and ranges (course_file.MILESTONE_ID, TYPE_NAME,
SHAPE_PARAMS, DRAWING_PARAMS, ...). It is kept in the repository as courses/course.schema.json,
and each course.yaml names it on its first line (MODELINE). After changing any of those, regenerate
it (a test fails until then):

    python3 -m course_format.json_schema --write      # or, to look: python3 -m course_format.json_schema

The loader (course_file) validates every course file against the same document with jsonschema
(`problems`), each error turned into the field it is about and a sentence, which the loader prints
as `FILE:LINE: FIELD: message`; what a schema cannot say (a regular expression that compiles, a
`node` naming an earlier step, LO <= HI, ...) the loader checks itself. No ROS import.
"""
from __future__ import annotations

import argparse
import functools
import json
import os
import sys
from typing import Any, Dict, List, Optional, Sequence, Tuple

import jsonschema
from jsonschema import Draft7Validator

# course_file validates with this module, and this module reads course_file's keys, names and
# ranges: each uses the other only when called, so either may be imported first
from course_format import causes, course_file, saved, schema

FILE = "course.schema.json"  # in courses/, beside the course folders
MODELINE = "# yaml-language-server: $schema=../%s" % FILE  # a course.yaml's first line
DRAFT = "http://json-schema.org/draft-07/schema#"
REGENERATE = "python3 -m course_format.json_schema --write"

Path = Tuple[Any, ...]

TYPES = {schema.STR: "string", schema.NUMBER: "number", schema.INT: "integer", schema.BOOL: "boolean",
         schema.LIST: "array", schema.MAP: "object"}  # schema.ANY: no type
WORDS = {"string": "a string", "number": "a number", "integer": "an integer", "boolean": "true or false",
         "array": "a list", "object": "a mapping", "null": "nothing"}

COURSE_DOCS = {
    "name": "the course's name: grade --course, the gradebook",
    "title": "the course's title, as the report shows it",
    "solution": "the reference solution's folder, relative to the course folder (answers: never in the student image)",
    "samples": "the graded samples' folder, each sample with its expected.json (answers too)",
    "starter": "the code the texts hand out, if any (similarity counts it as boilerplate)",
    "milestones": "the course's milestones, each graded on its own",
}
MILESTONE_DOCS = {
    "id": "[a-z][a-z0-9_]*: --only, the gradebook's columns, JUnit names",
    "title": "what the milestone asks, in a line",
    "text": "where the text asks it (e.g. its section)",
    "points": "the milestone's points",
    "packages": "the package names the text fixes; [] = the course workspace itself",
    "world": "trusted nodes started before the student's (course_format.schema.WORLDS)",
    "time_limit": "seconds the milestone's run may take",
    "steps": "a data milestone: primitives run in order (course_format.schema.PRIMITIVES)",
    "check": "a Python check: NAME.test in the course's checks/ folder",
    "equivalent": "mutants course-lint makes of the reference that no check can kill, OPERATOR_N: the reason a "
                  "reviewer reads (docs/course_lint.md)",
}
FIND_KEYS = {"publishes": "a topic", "subscribes": "a topic", "advertises": "a service", "node": "/NAME"}
PREDICATE_VALUES: Dict[str, Dict[str, Any]] = {
    "equals": {"description": "the value equals V"},
    "differs": {"description": "the value is other than V"},
    "approx": {"type": "number", "description": "the value is within tolerance of this number"},
    "tolerance": {"type": "number", "minimum": 0, "description": "goes with approx: how far the value may be"},
    "matches": {"type": "string", "description": "a regular expression searched in the value's text"},
    "between": {"title": "between", "type": "array", "minItems": 2, "maxItems": 2, "items": {"type": "number"},
                "description": "[LO, HI]: the value is a number from LO to HI"},
    "nonempty": {"type": "boolean", "description": "true: the value is not empty"},
}

# Sentences for the errors of a subschema with this title, by keyword ("*": any keyword), in
# %-format with value (the value found), known (what it may be) and close (" (did you mean X?)").
MESSAGES = {
    ("course.yaml", "type"): "expected a mapping with name, title and milestones",
    ("milestones", "minItems"): "no milestone",
    ("milestone id", "pattern"): "%(value)r: an id is lower case letters, digits and _, a letter first",
    ("package", "*"): "%(value)r is not a catkin package name",
    ("world", "*"): "%(value)r: no such world (known: %(known)s)",
    ("check", "pattern"): "%(value)r: name a rostest file, NAME.test, in the course's checks/ folder",
    ("step", "type"): "a step is one primitive with its parameters, e.g. {publishes: {topic: /chatter}} "
                      "(known: %(known)s)",
    ("step", "additionalProperties"): "no such primitive%(close)s (known: %(known)s)",
    ("type name", "*"): "%(value)r: a type is PKG/Name",
    ("cause", "*"): "%(value)r is no cause%(close)s (known: course_format/causes.py)",
    ("shape", "*"): "%(value)r: a shape is one of %(known)s",
    ("find", "*"): "one of {publishes: TOPIC}, {subscribes: TOPIC}, {advertises: SERVICE}, {node: /NAME}",
    ("start", "oneOf"): "give one of rosrun: 'PKG SCRIPT' or roslaunch: 'PKG FILE.launch'",
    ("rosrun", "pattern"): "%(value)r: expected 'PKG SCRIPT'",
    ("roslaunch", "pattern"): "%(value)r: expected 'PKG FILE.launch'",
    ("equivalent", "type"): "expected a mapping of mutant names to reasons, e.g. {rate_div10_1: \"section 2 fixes "
                            "no rate\"}, got %(value)r",
    ("mutant name", "*"): "%(value)r: name a mutant as course-lint does, OPERATOR_N (e.g. rate_div10_1)",
    ("reason", "*"): "expected the reason a reviewer reads (why no check can kill it), got %(value)r",
    ("saved name", "*"): "%(value)r: a saved value's name is letters, digits and _, not a digit first",
    ("answer field", "*"): "expected the answer's field (name2, pose.x), got %(value)r",
    ("command-line word", "*"): "%(value)r: a command-line word is a string or a number",
    ("predicate", "type"): "expected a predicate, a mapping of %(known)s; got %(value)r",
    ("between", "*"): "expected [LO, HI], two numbers, LO <= HI; got %(value)r",
}
MESSAGES[("step", "minProperties")] = MESSAGES[("step", "maxProperties")] = MESSAGES[("step", "type")]
MESSAGES[("predicate", "minProperties")] = MESSAGES[("predicate", "type")]
GENERIC = {
    "enum": "%(value)r: expected one of %(known)s",
    "pattern": "%(value)r: expected text matching %(known)s",
    "minimum": "%(value)r: expected a number from %(known)s",
    "exclusiveMinimum": "%(value)r: expected a number above %(known)s",
    "maximum": "%(value)r: expected a number up to %(known)s",
    "exclusiveMaximum": "%(value)r: expected a number below %(known)s",
    "minItems": "expected at least %(known)s items, got %(value)r",
    "maxItems": "expected at most %(known)s items, got %(value)r",
    "minProperties": "expected at least %(known)s fields, got %(value)r",
    "maxProperties": "expected at most %(known)s fields, got %(value)r",
}


def _ref(name: str) -> Dict[str, str]:
    return {"$ref": "#/definitions/%s" % name}


def _described(out: Dict[str, Any], doc: str) -> Dict[str, Any]:
    return dict(out, description=doc) if doc else out


def _param(primitive: schema.Primitive, p: schema.Param) -> Dict[str, Any]:
    """A step parameter: its kind, default and doc, and what the loader's names and ranges add."""
    out: Dict[str, Any] = {"description": p.doc} if p.doc else {}
    if p.kind in TYPES:
        out["type"] = TYPES[p.kind]
    if p.default is not None:
        out["default"] = p.default
    if p.name == "cause":
        out.update(title="cause", enum=list(causes.BY_KEY))
    elif p.name == "type" and p.kind == schema.STR:
        out.update(title="type name", pattern=course_file.TYPE_NAME.pattern)
    elif p.name in ("messages", "services", "actions"):
        out["items"] = {"title": "type name", "type": "string", "pattern": course_file.TYPE_NAME.pattern}
    elif p.name == "find":
        out.update(title="find", properties={k: {"type": "string", "description": v} for k, v in FIND_KEYS.items()},
                   additionalProperties=False, minProperties=1, maxProperties=1)
    elif p.name in ("rosrun", "roslaunch"):
        out.update(title=p.name, pattern=course_file.COMMAND.pattern)
    elif p.name == "args":
        out["items"] = {"title": "command-line word", "type": ["string", "number", "boolean"]}
    elif p.name == "shape":
        out.update(title="shape", enum=list(course_file.SHAPE_PARAMS))
    elif p.name == "save":
        out.update(propertyNames={"title": "saved name", "type": "string", "pattern": "^%s$" % saved.NAME.pattern},
                   additionalProperties={"title": "answer field", "type": "string", "minLength": 1})
    elif p.name in ("fields", "expect"):
        out = dict(out, **_ref("predicate")) if primitive.name == "param_is" else dict(
            out, additionalProperties=_ref("predicate"))
    out.update(course_file.RANGES.get((primitive.name, p.name), {}))
    return out


def _primitive(primitive: schema.Primitive) -> Dict[str, Any]:
    required = [p.name for p in primitive.params if p.required]
    out = {"title": primitive.name,
           "description": "%s (%s)" % (primitive.doc, "an action" if primitive.action else "a check"),
           # `start:` with nothing after it is a step with no parameters, which only a step that
           # needs none may be
           "type": "object" if required else ["object", "null"],
           "properties": {p.name: _param(primitive, p) for p in primitive.params},
           "additionalProperties": False}
    if required:
        out["required"] = required
    if {"rosrun", "roslaunch"} <= set(out["properties"]):
        out["oneOf"] = [{"required": ["rosrun"]}, {"required": ["roslaunch"]}]
    return out


def _course_keys() -> Dict[str, Dict[str, Any]]:
    """The schema of each key a course file may have, in course_file.COURSE_KEYS' order (a key the
    generator does not know yet gets {}: test_json_schema names it)."""
    known: Dict[str, Dict[str, Any]] = {key: {"type": "string"} for key in ("name", "title", "solution", "samples",
                                                                         "starter")}
    known["milestones"] = {"title": "milestones", "type": "array", "minItems": 1, "items": _ref("milestone")}
    return {key: _described(known.get(key, {}), COURSE_DOCS.get(key, "")) for key in course_file.COURSE_KEYS}


def _milestone_keys() -> Dict[str, Dict[str, Any]]:
    """The schema of each key a milestone may have, in course_file.MILESTONE_KEYS' order (likewise)."""
    known: Dict[str, Dict[str, Any]] = {
        "id": {"title": "milestone id", "type": "string", "pattern": course_file.MILESTONE_ID.pattern},
        "title": {"type": "string"},
        "text": {"type": "string"},
        "points": {"type": "number", "minimum": 0, "default": course_file.DEFAULT_POINTS},
        "packages": {"type": "array", "default": [],
                     "items": {"title": "package", "type": "string", "pattern": course_file.PACKAGE_NAME.pattern}},
        "world": {"type": "array", "default": [], "items": {"title": "world", "enum": list(schema.WORLDS)}},
        "time_limit": {"type": "number", "exclusiveMinimum": 0, "default": course_file.DEFAULT_TIME_LIMIT_S},
        "steps": {"type": "array", "items": _ref("step")},
        "check": {"title": "check", "type": "string", "pattern": course_file.CHECK_FILE.pattern},
        "equivalent": {"title": "equivalent", "type": "object", "default": {},
                       "propertyNames": {"title": "mutant name", "type": "string",
                                         "pattern": course_file.MUTANT_NAME.pattern},
                       "additionalProperties": {"title": "reason", "type": "string", "pattern": r"\S"}},
    }
    return {key: _described(known.get(key, {}), MILESTONE_DOCS.get(key, "")) for key in course_file.MILESTONE_KEYS}


def document() -> Dict[str, Any]:
    """The JSON Schema of a course file."""
    return {
        "$schema": DRAFT,
        "title": "course.yaml",
        "description": "A course folder's course.yaml (docs/course_format.md). Generated from course_format "
                       "(`%s`): do not edit." % REGENERATE,
        "type": "object",
        "properties": _course_keys(),
        "required": ["name", "title", "milestones"],
        "additionalProperties": False,
        "definitions": {
            "milestone": {
                "title": "milestone",
                "type": "object",
                "properties": _milestone_keys(),
                "required": ["id", "title", "text"],
                "additionalProperties": False,
                "oneOf": [{"required": ["steps"]}, {"required": ["check"]}],
            },
            "step": {
                "title": "step",
                "description": "one primitive with its parameters",
                "type": "object",
                "properties": {name: _primitive(p) for name, p in schema.PRIMITIVES.items()},
                "additionalProperties": False,
                "minProperties": 1,
                "maxProperties": 1,
            },
            "predicate": {
                "title": "predicate",
                "description": "a predicate on a value; several keys must all hold",
                "type": "object",
                "properties": {key: PREDICATE_VALUES.get(key, {}) for key in schema.PREDICATE_KEYS},
                "additionalProperties": False,
                "minProperties": 1,
                "dependencies": {"tolerance": ["approx"]},
            },
        },
    }


def text() -> str:
    """The document as the repository keeps it."""
    return json.dumps(document(), indent=2, ensure_ascii=False) + "\n"


def _strict_integer(checker: Any, value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


@functools.lru_cache(maxsize=None)
def validator() -> Any:
    """A jsonschema validator of the document, whose integer is an int (JSON Schema's also takes 2.0,
    which a count or a colour channel is not)."""
    kind = jsonschema.validators.extend(
        Draft7Validator, type_checker=Draft7Validator.TYPE_CHECKER.redefine("integer", _strict_integer))
    return kind(document())


def problems(data: Any) -> List[Tuple[Path, str]]:
    """What is wrong with a course file's data by the schema: (the field's path, a sentence), in the
    order jsonschema finds them, each once."""
    check = validator()
    found: List[Tuple[Path, str]] = []
    for error in check.iter_errors(data):
        for problem in _explain(check, error):
            if problem not in found:
                found.append(problem)
    return found


def _explain(check: Any, error: jsonschema.ValidationError) -> List[Tuple[Path, str]]:
    """One jsonschema error as (path, sentence)s; none for an error beside the wrong type of its value
    (a value of the wrong type is told its type only)."""
    path: Path = tuple(error.absolute_path)
    if list(error.absolute_schema_path)[-2:-1] == ["propertyNames"]:  # about a key: its path is the key's
        path += (error.instance,)
    where: Dict[str, Any] = error.schema if isinstance(error.schema, dict) else {}
    keyword, value, instance = error.validator, error.validator_value, error.instance
    types = where.get("type")
    if keyword != "type" and types is not None and not any(
            check.is_type(instance, t) for t in ([types] if isinstance(types, str) else types)):
        return []
    title = where.get("title", "")
    if keyword == "required":
        return [(path + (key,), "missing" + (" (%s)" % where["properties"][key]["description"]
                                            if where.get("properties", {}).get(key, {}).get("description") else ""))
                for key in value if key not in instance]
    if keyword == "dependencies":
        return [(path + (key,), "a %s goes with %s" % (key, " and ".join(needs)))
                for key, needs in value.items() if key in instance and any(n not in instance for n in needs)]
    if keyword == "additionalProperties" and value is False and (title, "*") not in MESSAGES:
        known = list(where.get("properties", {}))
        template = MESSAGES.get((title, keyword), "unknown field%(close)s (known: %(known)s)")
        return [(path + (key,), template % _words(template, key, known)) for key in instance if key not in known]
    if keyword == "oneOf" and title == "milestone":
        return [(path, "give either steps (data) or check (a Python check's rostest file), not %s"
                 % ("both" if "steps" in instance else "neither"))]
    template = MESSAGES.get((title, keyword)) or MESSAGES.get((title, "*"))
    known = _known(title, value, where)
    if template is not None:
        return [(path, template % _words(template, instance, known))]
    if keyword == "type":
        kinds = [value] if isinstance(value, str) else value
        return [(path, "expected %s, got %r" % (" or ".join(WORDS.get(k, k) for k in kinds), instance))]
    if keyword in GENERIC:
        return [(path, GENERIC[keyword] % {"value": instance, "known": ", ".join(map(str, known))})]
    return [(path, error.message)]


def _known(title: str, value: Any, where: Dict[str, Any]) -> List[Any]:
    """What the value may be, for a sentence: an enum's values, a step's primitives, a bound."""
    if "enum" in where:
        return list(where["enum"])
    if title in ("step", "predicate"):
        return list(where.get("properties", {}))
    return list(value) if isinstance(value, (list, tuple)) else [value]


def _words(template: str, value: Any, known: Sequence[Any]) -> Dict[str, Any]:
    """The words a sentence's template names: the value, what it may be, a close one it may mean."""
    close = [k for k in known if isinstance(k, str) and course_file._close(str(value), k)] \
        if "%(close)s" in template else []
    return {"value": value, "known": ", ".join(map(str, known)),
            "close": " (did you mean %s?)" % close[0] if close else ""}


def default_file() -> str:
    """courses/course.schema.json of this checkout."""
    return os.path.join(os.path.dirname(course_file.builtin_course_dir()), FILE)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m course_format.json_schema", description=__doc__.split("\n")[0])
    parser.add_argument("--write", nargs="?", const="", metavar="FILE",
                        help="write the schema to FILE (default: courses/%s of this checkout) instead of "
                             "printing it" % FILE)
    args = parser.parse_args(argv)
    if args.write is None:
        sys.stdout.write(text())
        return 0
    target = args.write or default_file()
    with open(target, "w", encoding="utf-8") as f:
        f.write(text())
    print("wrote %s" % target, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
