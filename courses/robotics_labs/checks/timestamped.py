"""Lab 2 checkpoint 1 (002 section 3): what a TimestampString publisher sends and what its
subscriber prints, read without assuming the student's field names or number formats.

The text names no fields: the message holds "the user input (a string), and the timestamp (a
number)". So the fields are found by type, and a printed time is read in whatever unit the
student's clock call gives (seconds from rospy.get_time(), nanoseconds from a printed rospy.Time).
"""
from __future__ import annotations

import re
from typing import List, NamedTuple, Optional, Sequence, Tuple

from closest_line import GAP, SPACE, Form, literal, pattern

STRING_TYPES = ("string",)
NUMBER_TYPES = ("float64", "float32", "int64", "uint64", "int32", "uint32", "int16", "uint16", "int8", "uint8",
                "time")
# Units a student's clock value may come in: s, ms, us, ns (rospy.Time printed as an integer).
SCALES = (1.0, 1e3, 1e6, 1e9)

# "Message: <message>, Sent at: <timestamp>, Received at: <timestamp>" (section 3.1, subscriber
# step 2), with the spacing print(a, b, c) adds around commas tolerated. The form is the pattern
# the check searches for, and says where a line departs from it (closest_line).
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
MESSAGE = "<message>"
FORM = Form(["Message:", SPACE, pattern(r"(?P<message>.*?)", MESSAGE), GAP, ",", SPACE,
             "Sent at:", SPACE, pattern(r"(?P<sent>%s)" % _NUMBER, "<timestamp>", greedy=True), GAP, ",", SPACE,
             "Received at:", SPACE, pattern(r"(?P<received>%s)" % _NUMBER, "<timestamp>", greedy=True)])
PRINTED = re.compile(FORM.pattern, re.IGNORECASE)
PROMPT = "Please enter a line of text and press <Enter>:"
_WORDS_APART = pattern(r"\s+", " ")
PROMPT_FORM = Form(["enter", _WORDS_APART, "a", _WORDS_APART, "line", _WORDS_APART, "of", _WORDS_APART, "text"])
_PROMPT_WORDS = re.compile(PROMPT_FORM.pattern, re.IGNORECASE)
_AROUND_MESSAGE = pattern(r"['\"\s]*", "")  # what line_for strips around a message


def printed_form(message: str) -> Form:
    """The form of the line the subscriber prints for `message` (as line_for reads it)."""
    return FORM.replaced(MESSAGE, (_AROUND_MESSAGE,) + literal(message, fold=False) + (_AROUND_MESSAGE,))


class Fields(NamedTuple):
    """The message's text field and time field (names are the student's)."""

    text: Optional[str]
    time: Optional[str]
    time_type: Optional[str]


def find_fields(names: Sequence[str], types: Sequence[str]) -> Tuple[Fields, str]:
    """The string field and the number field of a message type given its slot names and types,
    and '' if that is all it holds, else what is wrong, in words (the text: "your new message type
    should contain only a single message and timestamp")."""
    strings = [n for n, t in zip(names, types) if t in STRING_TYPES]
    numbers = [(n, t) for n, t in zip(names, types) if t in NUMBER_TYPES]
    fields = Fields(strings[0] if strings else None, numbers[0][0] if numbers else None,
                    numbers[0][1] if numbers else None)
    listed = ", ".join("%s %s" % (t, n) for n, t in zip(names, types)) or "no fields"
    if len(strings) != 1 or len(numbers) != 1 or len(names) != 2:
        return fields, ("it should hold one string (the text) and one number (the timestamp), "
                        "and nothing else; it has: %s" % listed)
    return fields, ""


def as_seconds(value: float, near: float) -> float:
    """`value` read as a clock in s, ms, us or ns: whichever unit lands nearest `near` (seconds)."""
    return min((value / scale for scale in SCALES), key=lambda s: abs(s - near))


def entered_in_time(stamp: float, typed_at: float, received_at: float, whole_seconds: bool) -> bool:
    """Whether a timestamp (seconds) lies between typing the line and its arrival, give or take
    half a second (a whole-second stamp may be up to a second early)."""
    return typed_at - 0.5 - (1.0 if whole_seconds else 0.0) <= stamp <= received_at + 0.5


def resolution(number_text: str) -> float:
    """How finely a printed number can match: 1e-6 for '1.123456', 1.0 for '1700000000'."""
    if "e" in number_text.lower() or "." not in number_text:
        return 1.0
    return 10.0 ** -len(number_text.split(".", 1)[1])


class PrintedLine(NamedTuple):
    message: str
    sent: str
    received: str


def printed_lines(output: str) -> List[PrintedLine]:
    """Every line of `output` in the text's subscriber format."""
    found = []
    for line in output.splitlines():
        match = PRINTED.search(line)
        if match:
            found.append(PrintedLine(match.group("message"), match.group("sent"), match.group("received")))
    return found


def line_for(output: str, message: str) -> Optional[PrintedLine]:
    """The last printed line for `message` (surrounding quotes and spaces ignored), or None."""
    for line in reversed(printed_lines(output)):
        if line.message.strip().strip("'\"").strip() == message:
            return line
    return None


def prompt_count(output: str) -> int:
    """How many times the publisher asked for a line of text (the text's prompt, any case)."""
    return len(_PROMPT_WORDS.findall(output))


def time_matches(printed: str, expected: float) -> bool:
    """Whether a printed time is `expected` (seconds) to the precision it was printed with."""
    seconds = as_seconds(float(printed), expected)
    scale = float(printed) / seconds if seconds else 1.0
    return abs(seconds - expected) <= resolution(printed) / scale + 1e-6
