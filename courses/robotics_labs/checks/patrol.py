"""Lab 2 checkpoint 3 (002 section 5): how the text's call fills a student's patrol request.

The text's call is `rosservice call /[turtle_name]/patrol vel omega x y theta`, and it "may look
like" that: the turtle is named by the service (one /<turtle>/patrol per turtle) or, in a design
the course accepts too (courses/robotics_labs/milestones/checkpoint3.md), by the request of one shared service.
Either way the numbers go in the text's order; the field names are the student's.
"""
from __future__ import annotations

from typing import List, NamedTuple, Optional, Sequence, Tuple

from circles import PatrolRequest

NUMBER_TYPES = ("float32", "float64", "int8", "int16", "int32", "int64", "uint8", "uint16", "uint32", "uint64")


class Layout(NamedTuple):
    """Which request field takes the turtle's name (None: the service's name names the turtle)."""

    slots: Tuple[str, ...]
    name_field: Optional[str]

    def arguments(self, turtle: str, req: PatrolRequest) -> List[object]:
        """The request's values in its fields' order: the name where it goes, the numbers in the text's order."""
        numbers = iter(req)
        return [turtle if slot == self.name_field else next(numbers) for slot in self.slots]


def fields_words(slots: Sequence[str], types: Sequence[str]) -> str:
    """'vel (float32), omega (float32), ...' for a failure message."""
    return ", ".join("%s (%s)" % (s, t) for s, t in zip(slots, types)) or "no fields"


def layout(slots: Sequence[str], types: Sequence[str], named_by_service: bool) -> Tuple[Optional[Layout], str]:
    """How the text's five numbers (and, for a shared service, the turtle's name) fill a request of
    these fields; (None, what is wrong) when they cannot."""
    numbers = [s for s, t in zip(slots, types) if t in NUMBER_TYPES]
    strings = [s for s, t in zip(slots, types) if t == "string"]
    if named_by_service:
        if len(slots) == 5 and len(numbers) == 5:
            return Layout(tuple(slots), None), ""
        return None, "its request has %s: the text's call gives it five numbers, vel omega x y theta" % (
            fields_words(slots, types))
    if len(strings) == 1 and len(numbers) == 5 and len(slots) == 6:
        return Layout(tuple(slots), strings[0]), ""
    if not strings:
        return None, ("its request names no turtle (%s): one server for every turtle needs the turtle's name in its "
                      "request, and one server per turtle needs a service of its own for each, /<turtle>/patrol as "
                      "the text calls it" % fields_words(slots, types))
    return None, ("its request has %s: a shared service needs the turtle's name (one string) and the text's five "
                  "numbers, vel omega x y theta" % fields_words(slots, types))


def call_words(service: str, plan: Layout, turtle: str, req: PatrolRequest) -> str:
    """The call as a student would type it: `rosservice call /patrol turtle1 1 1 3 3 1.57`."""
    values = plan.arguments(turtle, req)
    return "rosservice call %s %s" % (service, " ".join(v if isinstance(v, str) else "%g" % v for v in values))
