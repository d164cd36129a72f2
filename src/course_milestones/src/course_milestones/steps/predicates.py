"""The pure logic of a course file's checks, apart from ROS: predicates on values, field paths into
messages, a publisher's rate from arrival times, and a message in one line for a failure's text.

A course file's predicate (`{equals: V}`, `{differs: V}`, `{approx: V, tolerance: T}`, `{matches: REGEX}`,
`{between: [LO, HI]}`, `{nonempty: true}`; several keys in one mapping must all hold) is data a
TA wrote, and the value it is applied to is whatever a student's node sent. So `holds` never
raises: a predicate that cannot hold on a value says why in its Verdict, and `problem` tells a
course file's mistake (a bad regular expression, a range upside down) before anything runs.
"""
from __future__ import annotations

import math
import numbers
import re
from typing import Any, Mapping, NamedTuple, Optional, Sequence

DEFAULT_TOLERANCE = 1e-3
# A measured rate may miss its bounds by this fraction: arrival times jitter with the machine's load.
RATE_SLACK = 0.05
DESCRIBE_LIMIT = 300
_LIST_ITEMS = 8        # items of a list shown in a description
_DEPTH = 6             # nesting shown in a description
_PATH_PART = re.compile(r"[^.\[\]]+")
_INDEX = re.compile(r"^-?[0-9]+$")


class Verdict(NamedTuple):
    """Whether a value satisfies a predicate, and the value in words with what was expected."""

    holds: bool
    text: str


class FieldMissing(KeyError):
    """A field path names a field the value does not have (its text says which, and what there is)."""

    def __str__(self) -> str:
        return str(self.args[0])


# -- predicates ---------------------------------------------------------------------------------------

def _is_number(value: object) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def problem(predicate: object) -> Optional[str]:
    """What is wrong with a course file's predicate, or None when it can be applied."""
    if not isinstance(predicate, Mapping) or not predicate:
        return "a predicate is a mapping such as {equals: V}, {differs: V}, {approx: V, tolerance: T}, " \
               "{matches: REGEX}, {between: [LO, HI]} or {nonempty: true}, not %s" % _short(repr(predicate), 80)
    unknown = [str(k) for k in predicate if k not in ("equals", "differs", "approx", "tolerance", "matches",
                                                      "between", "nonempty")]
    if unknown:
        return "unknown predicate key %s" % ", ".join(unknown)
    if "tolerance" in predicate and "approx" not in predicate:
        return "tolerance goes with approx"
    if "approx" in predicate and not _is_number(predicate["approx"]):
        return "approx takes a number, not %r" % (predicate["approx"],)
    tolerance = predicate.get("tolerance", DEFAULT_TOLERANCE)
    if not _is_number(tolerance) or not tolerance >= 0:
        return "tolerance takes a number >= 0, not %r" % (tolerance,)
    if "matches" in predicate:
        if not isinstance(predicate["matches"], str):
            return "matches takes a regular expression (text), not %r" % (predicate["matches"],)
        try:
            re.compile(predicate["matches"])
        except re.error as err:
            return "matches: %r is not a regular expression (%s)" % (predicate["matches"], err)
    if "between" in predicate:
        bounds = predicate["between"]
        if (not isinstance(bounds, (list, tuple)) or len(bounds) != 2 or not all(_is_number(b) for b in bounds)
                or not bounds[0] <= bounds[1]):
            return "between takes [LO, HI], two numbers with LO <= HI, not %r" % (bounds,)
    if "nonempty" in predicate and not isinstance(predicate["nonempty"], bool):
        return "nonempty takes true or false, not %r" % (predicate["nonempty"],)
    return None


def holds(predicate: object, value: Any) -> Verdict:
    """Whether `value` satisfies every key of `predicate`; never raises."""
    wrong = problem(predicate)
    shown = describe(value, 120)
    if wrong:
        return Verdict(False, "%s cannot be judged: %s" % (shown, wrong))
    for test in (_equals, _differs, _approx, _matches, _between, _nonempty):
        failed = test(predicate, value)
        if failed:
            return Verdict(False, "is %s, %s" % (shown, failed))
    return Verdict(True, "is %s, as %s" % (shown, expectation(predicate)))


def expectation(predicate: Mapping) -> str:
    """What a (valid) predicate asks, in words: "equal to 3 and nonempty"."""
    words = []
    if "equals" in predicate:
        words.append("equal to %s" % describe(predicate["equals"], 80))
    if "differs" in predicate:
        words.append("other than %s" % describe(predicate["differs"], 80))
    if "approx" in predicate:
        words.append("within %s of %s" % (_num(predicate.get("tolerance", DEFAULT_TOLERANCE)), _num(predicate["approx"])))
    if "matches" in predicate:
        words.append("matching %r" % predicate["matches"])
    if "between" in predicate:
        words.append("between %s and %s" % tuple(_num(b) for b in predicate["between"]))
    if "nonempty" in predicate:
        words.append("nonempty" if predicate["nonempty"] else "empty")
    return " and ".join(words)


def _same(value: Any, other: Any) -> bool:
    try:
        return bool(value == other)
    except Exception:  # noqa: BLE001 - a value whose == raises is not equal
        return False


def _equals(predicate: Mapping, value: Any) -> str:
    if "equals" not in predicate or _same(value, predicate["equals"]):
        return ""
    return "expected %s" % describe(predicate["equals"], 80)


def _differs(predicate: Mapping, value: Any) -> str:
    if "differs" not in predicate or not _same(value, predicate["differs"]):
        return ""
    return "expected a value other than %s" % describe(predicate["differs"], 80)


def _approx(predicate: Mapping, value: Any) -> str:
    if "approx" not in predicate:
        return ""
    wanted, tolerance = predicate["approx"], predicate.get("tolerance", DEFAULT_TOLERANCE)
    if not _is_number(value):
        return "not a number, expected %s (within %s)" % (_num(wanted), _num(tolerance))
    try:
        close = abs(float(value) - float(wanted)) <= tolerance
    except (OverflowError, ValueError):
        close = False
    return "" if close else "expected %s (within %s)" % (_num(wanted), _num(tolerance))


def _matches(predicate: Mapping, value: Any) -> str:
    if "matches" not in predicate:
        return ""
    found = re.search(predicate["matches"], text_of(value), re.MULTILINE)
    return "" if found else "expected it to match %r" % predicate["matches"]


def _between(predicate: Mapping, value: Any) -> str:
    if "between" not in predicate:
        return ""
    low, high = predicate["between"]
    if not _is_number(value):
        return "not a number, expected one between %s and %s" % (_num(low), _num(high))
    try:
        inside = low <= value <= high
    except (OverflowError, ValueError, TypeError):
        inside = False
    return "" if inside else "expected a number between %s and %s" % (_num(low), _num(high))


def _nonempty(predicate: Mapping, value: Any) -> str:
    if "nonempty" not in predicate:
        return ""
    try:
        empty = value is None or (hasattr(value, "__len__") and len(value) == 0)
    except Exception:  # noqa: BLE001 - a length that cannot be had: not empty
        empty = False
    if predicate["nonempty"] == (not empty):
        return ""
    return "expected %s" % ("a nonempty value" if predicate["nonempty"] else "an empty value")


def text_of(value: Any) -> str:
    """A value as the text `matches` searches: a string itself, bytes decoded, else str()."""
    if isinstance(value, str):
        return value
    if isinstance(value, (bytes, bytearray)):
        return bytes(value).decode("utf-8", errors="replace")
    try:
        return str(value)
    except Exception:  # noqa: BLE001 - a value without a text
        return repr(type(value))


# -- field paths --------------------------------------------------------------------------------------

def field(value: Any, path: str) -> Any:
    """The part of `value` (a message, a mapping, a list) that `path` names: `linear.x`,
    `poses[0].x` or `poses.0.x`. Raises FieldMissing saying which part is not there."""
    parts = _PATH_PART.findall(path)
    if not parts:
        raise FieldMissing("%r names no field" % path)
    here = value
    for depth, part in enumerate(parts):
        seen = ".".join(parts[:depth]) or "the message"
        if isinstance(here, Mapping):
            if part not in here:
                raise FieldMissing("%s has no field %s (it has %s)" % (seen, part, ", ".join(map(str, here)) or
                                                                        "none"))
            here = here[part]
        elif isinstance(here, (list, tuple, bytes, bytearray)) and not isinstance(here, str):
            if not _INDEX.match(part) or not -len(here) <= int(part) < len(here):
                raise FieldMissing("%s has %d items, no item %s" % (seen, len(here), part))
            here = here[int(part)]
        elif part in _fields(here):
            here = getattr(here, part)
        else:
            names = _fields(here)
            raise FieldMissing("%s has no field %s (%s)" % (seen, part, "it has " + ", ".join(names) if names
                                                             else "it is %s" % describe(here, 60)))
    return here


def _fields(value: Any) -> Sequence[str]:
    """The field names of a generated message (its __slots__), else none."""
    slots = getattr(type(value), "__slots__", ())
    return [s for s in ([slots] if isinstance(slots, str) else slots) if not s.startswith("_")]


# -- rates --------------------------------------------------------------------------------------------

def rate(arrivals: Sequence[float]) -> Optional[float]:
    """Messages per second from arrival times (seconds, in order): intervals over the time they
    span. None with fewer than two, or when they span no time."""
    if len(arrivals) < 2:
        return None
    span = arrivals[-1] - arrivals[0]
    if not span > 0 or math.isinf(span):
        return None
    measured = (len(arrivals) - 1) / span
    return measured if math.isfinite(measured) else None


def rate_problem(measured: Optional[float], min_rate: Optional[float], max_rate: Optional[float],
                 slack: float = RATE_SLACK) -> Optional[str]:
    """What is wrong with a measured rate against [min_rate, max_rate] (either may be None), each
    bound widened by `slack`; None when it is within."""
    bounds = " and ".join(w for w in ("at least %s Hz" % _num(min_rate) if min_rate is not None else "",
                                      "at most %s Hz" % _num(max_rate) if max_rate is not None else "") if w)
    if not bounds:
        return None
    if measured is None:
        return "its rate cannot be measured (fewer than two messages); the text asks for %s" % bounds
    low = min_rate is not None and measured < min_rate * (1 - slack)
    high = max_rate is not None and measured > max_rate * (1 + slack)
    return "it publishes at %.3g Hz; the text asks for %s" % (measured, bounds) if low or high else None


# -- describing ---------------------------------------------------------------------------------------

def describe(value: Any, limit: int = DESCRIBE_LIMIT) -> str:
    """A value (a message, nested) on one line, at most `limit` characters: {linear: {x: 2.0, ...}}."""
    return _short(_words(value, 0), limit)


def _num(number: Any) -> str:
    """A number in few digits (%g), or as it is when %g cannot take it (a huge integer)."""
    try:
        return "%g" % number
    except (OverflowError, TypeError, ValueError):
        return str(number)


def _short(text: str, limit: int) -> str:
    return text if len(text) <= limit else text[:max(limit - 3, 0)] + "..."


def _words(value: Any, depth: int) -> str:
    if depth > _DEPTH:
        return "..."
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, float):
        return _num(value)
    if isinstance(value, (bytes, bytearray)):
        value = list(bytes(value))
    if isinstance(value, Mapping):
        items = ["%s: %s" % (k, _words(v, depth + 1)) for k, v in list(value.items())[:_LIST_ITEMS]]
        more = len(value) - len(items)
        return "{%s}" % ", ".join(items + (["... (%d more)" % more] if more > 0 else []))
    if isinstance(value, (list, tuple)):
        items = [_words(v, depth + 1) for v in value[:_LIST_ITEMS]]
        more = len(value) - len(items)
        return "[%s]" % ", ".join(items + (["... (%d more)" % more] if more > 0 else []))
    names = _fields(value)
    if names:
        return "{%s}" % ", ".join("%s: %s" % (n, _words(getattr(value, n, None), depth + 1)) for n in names)
    try:
        return str(value)
    except Exception:  # noqa: BLE001 - a value without a text
        return repr(type(value))
