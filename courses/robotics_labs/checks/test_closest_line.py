"""closest_line: the line a node printed nearest the text's form, and where it
departs from it, said in words (checkpoint1's `Recieved at:`)."""
import re
import string

import pytest
from hypothesis import assume, given, settings, strategies as st

import closest_line as cl
import timestamped as ts

RECEIVED = "Message: second line, Sent at: 1712345680.100000, Recieved at: 1712345680.200000"


def test_a_misspelt_word_is_shown_whole_where_it_departs():
    diff = cl.difference(ts.FORM, RECEIVED)
    assert diff.position == RECEIVED.index("Recieved") + 3  # 'i' where the text has 'e'
    assert (diff.printed, diff.expected, diff.cost) == ("Recieved", "Received", 2)
    assert cl.describe(diff) == (
        "the closest line printed, %r, differs from the text's form at character 54: 'Recieved' where the "
        "text has 'Received'" % RECEIVED)


@pytest.mark.parametrize("line, position, words", [
    # a comma left out after the student's free text: said where it belongs, not inside the text
    ("Message: second line Sent at: 1.5, Received at: 2", 20, "',' missing after 'Message: second line'"),
    # a line cut short: the first value stays Sent at's, the rest is what is missing
    ("Message: a, Sent at: 1.5", 24, "the line ends where the text goes on with ', Received at: <timestamp>'"),
    ("Message: a, Sent at: abc, Received at: 2", 21, "'abc' where the text has '<timestamp>'"),
    ("Message: a, Sentat: 1, Received at: 2", 16, "'Sentat' where the text has 'Sent at'"),
    ("Mesage: a, Sent at: 1, Received at: 2", 3, "'Mesage' where the text has 'Message'"),
    ("Message: a,, Sent at: 1; Received at: 2", 23, "';' where the text has ','"),
    ("Message: a, Sent at: 1, Received at:: 2", 36, "an extra ':' after 'Sent at: 1, Received at:'"),
])
def test_what_departs_and_where(line, position, words):
    diff = cl.difference(ts.FORM, line)
    assert diff.position == position, diff
    assert cl.describe(diff).endswith("at character %d: %s" % (position + 1, words))


def test_a_line_in_the_form_has_no_difference():
    for line in ("Message: hello, Sent at: 1.5, Received at: 2.5", "[INFO] message:hi , sent at:1 ,RECEIVED AT: 2e3",
                 "Message: a, b, Sent at: 1, Received at: 2"):
        assert ts.PRINTED.search(line) and cl.difference(ts.FORM, line) is None


def test_the_form_is_the_checks_pattern():
    """The check's pattern is built from its form, and is the one it always searched for."""
    number = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
    assert ts.PRINTED.pattern == (r"Message:\s*(?P<message>.*?)\s*,\s*Sent at:\s*(?P<sent>%s)\s*,\s*Received at:"
                                  r"\s*(?P<received>%s)" % (number, number))
    assert ts.FORM.display == "Message: <message>, Sent at: <timestamp>, Received at: <timestamp>"
    assert ts._PROMPT_WORDS.pattern == r"enter\s+a\s+line\s+of\s+text"


def test_the_form_for_one_message_names_it_case_and_all():
    form = ts.printed_form("second line")
    assert form.display == "Message: second line, Sent at: <timestamp>, Received at: <timestamp>"
    assert re.search(form.pattern, "Message: 'second line', Sent at: 1, Received at: 2", re.IGNORECASE)
    line = "MESSAGE: Second line, Sent at: 1, Received at: 2"
    assert not re.search(form.pattern, line, re.IGNORECASE)
    diff = cl.difference(form, line)
    assert (diff.position, diff.printed, diff.expected) == (9, "Second", "second")


def test_the_closest_of_several_lines_is_the_one_for_the_message():
    output = "\n".join([
        "warm up",
        RECEIVED.replace("second line", "warm up"),
        RECEIVED.replace("second line", "hello turtle"),
        "[INFO] [1712345680.3]: got a message",
        RECEIVED,
    ])
    words = cl.closest_words(output, ts.printed_form("second line"))
    assert words == "; " + cl.describe(cl.difference(ts.printed_form("second line"), RECEIVED))


def test_no_line_close_enough_gives_nothing():
    assert cl.closest_words("hello\nworld\n", ts.FORM) == ""
    assert cl.closest_words("", ts.FORM) == ""
    # a line in the form among others: nothing to point at
    assert cl.closest_words(RECEIVED + "\nMessage: x, Sent at: 1, Received at: 2", ts.FORM) == ""


def test_a_misspelt_prompt():
    words = cl.closest_words("Please entre a line of text:warm up\nwarm up\n", ts.PROMPT_FORM)
    assert words.endswith("at character 11: 'entre' where the text has 'enter'")


def test_of_equally_close_lines_the_last_printed():
    first = RECEIVED.replace("Recieved", "Receivd")
    last = RECEIVED.replace("Recieved", "Receved")
    assert cl.closest([first, last], ts.FORM).line == last
    assert cl.closest([last, first], ts.FORM).line == first


def test_long_output_and_long_lines_stay_quick():
    lines = ["x" * 5000] + ["noise %d" % n for n in range(5000)] + [RECEIVED]
    diff = cl.closest(lines, ts.FORM)
    assert diff.printed == "Recieved"


# -- property: a single edit of a line in the form is found where it was made ---------------------

NUMBERS = st.floats(min_value=0, max_value=2e9, allow_nan=False).map(lambda f: "%.6f" % f)
TEXT = st.text(alphabet=string.ascii_letters + " ", min_size=1, max_size=12).map(str.strip).filter(bool)
# characters an edit puts in: none that a value or optional whitespace next to it would take in
EDIT_CHARS = st.sampled_from(string.ascii_letters + ",:;!?#")


@st.composite
def edited_lines(draw):
    """A line the subscriber prints for a message, one of its characters that the form has (the
    text's words, the message) edited once: (line, edited line, kind of edit, where, character)."""
    message, sent, received = draw(TEXT), draw(NUMBERS), draw(NUMBERS)
    prefix, suffix = "Message: ", ", Sent at: "
    line = "%s%s%s%s, Received at: %s" % (prefix, message, suffix, sent, received)
    literal = [i for i in range(len(prefix.rstrip()))]
    literal += [len(prefix) + i for i, c in enumerate(message) if not c.isspace()]
    start = len(prefix) + len(message)
    literal += [start + i for i, c in enumerate(suffix) if not c.isspace() or i == 6]  # "Sent at"'s own space
    start = start + len(suffix) + len(sent)
    literal += [start + i for i, c in enumerate(", Received at:") if not c.isspace() or i == 10]
    at = draw(st.sampled_from(literal))
    kind = draw(st.sampled_from(("substitute", "insert", "delete")))
    char = draw(EDIT_CHARS)
    if kind == "substitute":
        assume(char.casefold() != line[at].casefold())
        edited = line[:at] + char + line[at + 1:]
    elif kind == "insert":
        edited = line[:at] + char + line[at:]
    else:
        edited = line[:at] + line[at + 1:]
    return message, line, edited, kind, at, char


@settings(max_examples=300, deadline=None)
@given(edited_lines())
def test_a_single_edit_is_found_where_it_is(case):
    message, line, edited, kind, at, char = case
    form = ts.printed_form(message)  # the form the check reads the line for its message with
    assume(not re.search(form.pattern, edited, re.IGNORECASE))  # an edit the check's pattern tolerates
    diff = cl.difference(form, edited)
    assert diff is not None and diff.cost == 1
    if kind == "substitute":
        assert diff.position == at
        assert diff.printed.casefold().find(char.casefold()) >= 0 and line[at] in diff.expected
    else:  # where the same character can go in (or out) with the same result, any of those places
        places = {i for i in range(len(line) + 1)  # (the text's words in any case)
                  if (line[:i] + char + line[i:] if kind == "insert" else line[:i] + line[i + 1:]).casefold()
                  == edited.casefold()}
        assert at in places and diff.position in places, (diff, places)
    assert ("at character %d: " % (diff.position + 1)) in cl.describe(diff)


@settings(max_examples=100, deadline=None)
@given(st.text(max_size=60))
def test_any_line_is_in_the_form_or_has_a_difference_inside_it(line):
    diff = cl.difference(ts.FORM, line)
    if ts.PRINTED.search(line):
        assert diff is None
    else:
        assert diff is not None and 0 <= diff.position <= len(line) and diff.cost > 0
        assert diff.before == line[:diff.position] and diff.printed in line
