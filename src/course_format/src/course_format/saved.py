"""Values a step saves for later steps, and the references to them: `call`'s `save: {NAME: FIELD}`
keeps a field of the answer (the turtle a spawn service named), which the same call's `expect`
and every later step name as `${NAME}` in their strings (`turtle: "${first}"`,
`topic: "/${first}/pose"`, `expect: {name2: {differs: "${first}"}}`).

A string that is one reference and nothing else is the value itself (a number stays a number);
a reference inside a longer string is the value's text, escaped in a regular expression (a
`prints` step's `pattern`, a predicate's `matches`), so that a saved name matches only itself.
No ROS: the course file loader checks the references, the check node resolves them.
"""
from __future__ import annotations

import re
from typing import Any, Dict, List, Mapping, Sequence

NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
REFERENCE = re.compile(r"\$\{([^{}]*)\}")
# The parameters that hold predicates: field -> predicate (param_is: one predicate).
PREDICATE_PARAMS = ("fields", "expect")


class Unknown(KeyError):
    """A reference to a name no step saved (the name is its argument)."""

    def __str__(self) -> str:
        return "${%s}" % self.args[0]


def references(value: Any) -> List[str]:
    """The names `value` (a parameter's value: a string, or lists and mappings of them) refers to,
    in order, each once."""
    found: List[str] = []
    for text in _strings(value):
        for name in REFERENCE.findall(text):
            if name not in found:
                found.append(name)
    return found


def _strings(value: Any):
    if isinstance(value, str):
        yield value
    elif isinstance(value, Mapping):
        for item in value.values():
            yield from _strings(item)
    elif isinstance(value, (list, tuple)):
        for item in value:
            yield from _strings(item)


def text_of(value: Any) -> str:
    """A saved value as it reads inside a string (a float in few digits)."""
    return "%g" % value if isinstance(value, float) else str(value)


def resolve(value: Any, saved: Mapping[str, Any], regex: bool = False) -> Any:
    """`value` with every reference replaced by its saved value; `regex`: `value`'s strings are
    regular expressions. Unknown for a name not in `saved`."""
    if isinstance(value, str):
        whole = REFERENCE.fullmatch(value)
        if whole is not None and not regex:
            return _get(saved, whole.group(1))
        return REFERENCE.sub(lambda m: (re.escape if regex else str)(text_of(_get(saved, m.group(1)))), value)
    if isinstance(value, Mapping):
        return {k: resolve(v, saved, regex) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [resolve(v, saved, regex) for v in value]
    return value


def resolve_step(primitive: str, params: Mapping[str, Any], saved: Mapping[str, Any],
                 later: Sequence[str] = ()) -> Dict[str, Any]:
    """A step's parameters with their references resolved, but those of the parameters `later`
    (a call's `expect`, resolved once its answer is saved); a `pattern` and a predicate's
    `matches` are regular expressions."""
    out: Dict[str, Any] = {}
    for key, value in params.items():
        if key in later:
            out[key] = value
        elif key == "pattern":
            out[key] = resolve(value, saved, regex=True)
        elif key in PREDICATE_PARAMS:
            out[key] = resolve_predicates(primitive, value, saved)
        else:
            out[key] = resolve(value, saved)
    return out


def resolve_predicates(primitive: str, value: Any, saved: Mapping[str, Any]) -> Any:
    """A step's predicates (`param_is`' one, or field -> predicate) resolved, `matches` as a regular
    expression."""
    def one(predicate: Any) -> Any:
        if not isinstance(predicate, Mapping):
            return resolve(predicate, saved)
        return {k: resolve(v, saved, regex=k == "matches") for k, v in predicate.items()}
    if primitive == "param_is" or not isinstance(value, Mapping):
        return one(value)
    return {field: one(predicate) for field, predicate in value.items()}


def _get(saved: Mapping[str, Any], name: str) -> Any:
    if name not in saved:
        raise Unknown(name)
    return saved[name]
