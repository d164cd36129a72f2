"""Compare a message definition with the one a text gives, field by field, in words a student
can act on ("Person: age is float32, the text says int32"). Field order is not compared: the
text's listing order is not something it asks to keep."""
from __future__ import annotations

from typing import List, Mapping, Sequence, Tuple


def field_problems(what: str, wanted: Mapping[str, str], got: Sequence[Tuple[str, str]]) -> List[str]:
    """Sentences for each missing, mistyped or extra field of `what` (empty when they match)."""
    have = dict(got)
    problems = []
    for name, kind in wanted.items():
        if name not in have:
            problems.append("%s has no field %s (%s %s)" % (what, name, kind, name))
        elif have[name] != kind:
            problems.append("%s: %s is %s, the text says %s" % (what, name, have[name], kind))
    extra = [n for n in have if n not in wanted]
    if extra:
        problems.append("%s has fields the text does not give: %s" % (what, ", ".join(extra)))
    return problems


def slots_of(msg_class) -> List[Tuple[str, str]]:
    """(name, type) of a generated rospy message class's fields."""
    return list(zip(msg_class.__slots__, msg_class._slot_types))
