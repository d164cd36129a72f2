"""The line a node printed that comes closest to the form a text asks for, and where it departs
from it: for a failure that says a node did not print a line in the text's format (`Recieved at:`
where the text has `Received at:`). No ROS import: plain logic, unit tested.

A form is a sequence of tokens, each with the regular expression a check matches it with, so that
a check's pattern can be built from its form (`Form.pattern`) and the two never disagree:
- a literal character (`literal`), compared case-insensitively unless told otherwise;
- a pattern (`pattern`): whitespace the text leaves free, a placeholder for a value (a number, the
  student's message), shown as the text shows it (`<timestamp>`).

A line is aligned with the form as an edit distance in which a pattern token consumes, at no cost,
any stretch of the line its expression matches in full, and a literal costs 1 to substitute, leave
out or add (half past the line's end: a line cut short); the form may begin and end anywhere in the
line (a check searches the line). The closest line is the one that costs least; where it departs is
the first edit of its alignment, as late as the least cost allows.
"""
from __future__ import annotations

import difflib
import re
from typing import Iterable, List, NamedTuple, Optional, Sequence, Tuple, Union


class Token(NamedTuple):
    display: str  # what the text shows for it
    regex: str  # what a check matches it with
    literal: bool  # one character, compared (case-insensitively when `fold`) with one of the line's
    fold: bool = True
    greedy: bool = False  # a pattern that takes all it can (a number is not split in two)


def literal(text: str, fold: bool = True) -> Tuple[Token, ...]:
    """`text` as literal tokens, one a character (a case-sensitive one is `(?-i:c)` in the pattern)."""
    def regex(c: str) -> str:
        escaped = c if c.isspace() else re.escape(c)
        return escaped if fold or c.lower() == c.upper() else "(?-i:%s)" % escaped
    return tuple(Token(c, regex(c), True, fold) for c in text)


def pattern(regex: str, display: str, greedy: bool = False) -> Token:
    """A stretch of the line matched by `regex` (in full), shown as `display`; `greedy`: only the
    longest such stretch counts (a number), else any (whitespace, a free text)."""
    return Token(display, regex, False, greedy=greedy)


SPACE = pattern(r"\s*", " ")  # optional whitespace, shown as a space
GAP = pattern(r"\s*", "")  # optional whitespace, shown as nothing

Piece = Union[str, Token, Sequence[Token]]


class Form:
    """A line the text asks for: literal text (a str piece, compared case-insensitively) and tokens."""

    def __init__(self, pieces: Iterable[Piece]) -> None:
        tokens: List[Token] = []
        for piece in pieces:
            if isinstance(piece, str):
                tokens.extend(literal(piece))
            elif isinstance(piece, Token):
                tokens.append(piece)
            else:
                tokens.extend(piece)
        self.tokens: Tuple[Token, ...] = tuple(tokens)
        self._compiled = [re.compile(t.regex, re.IGNORECASE | re.DOTALL) if not t.literal else None
                          for t in self.tokens]

    @property
    def pattern(self) -> str:
        """The regular expression of the whole form (searched in a line, re.IGNORECASE)."""
        return "".join(t.regex for t in self.tokens)

    @property
    def display(self) -> str:
        return "".join(t.display for t in self.tokens)

    def replaced(self, display: str, tokens: Sequence[Token]) -> "Form":
        """This form with each pattern token shown as `display` replaced by `tokens` (a placeholder
        filled with the value the check expects there)."""
        out: List[Token] = []
        for t in self.tokens:
            out.extend(tokens if not t.literal and t.display == display else (t,))
        return Form([out])

    def literal_count(self) -> int:
        """How many literal characters the form has."""
        return sum(1 for t in self.tokens if t.literal)


# One step of an alignment: its kind, the tokens [i0, i1) and the line's characters [j0, j1) it covers.
MATCH, CONSUME, SUBSTITUTE, EXTRA, MISSING = "match", "consume", "substitute", "extra", "missing"
Step = Tuple[str, int, int, int, int]


class Difference(NamedTuple):
    """Where `line` departs from the form: at `position` (0-based), `printed` (the line's text
    there, '' when it leaves something out) where the form has `expected` ('' for an extra text);
    `before`: the line's text just before `position`; `cost`: the alignment's edits."""

    line: str
    position: int
    printed: str
    expected: str
    before: str
    cost: float


INF = float("inf")
# The costs, in units of (the line's length + 1): an edit 2, a token missing after the line's end 1
# (half an edit); below them, each character of the line left after the form's end costs 1/unit, so
# that of alignments with as many edits the one that reads more of the line wins ("at:: 2": an
# extra ':', not a value missing and ': 2' left over).
EDIT, TAIL = 2, 1


def _same(token: Token, char: str) -> bool:
    want = token.display
    return want.casefold() == char.casefold() if token.fold else want == char


def _ends(form: Form, line: str) -> List[List[List[int]]]:
    """For each pattern token and each start j, the ends k such that the token matches line[j:k]."""
    n = len(line)
    by_regex = {}  # optional whitespace stands in many places: each expression is tried once
    ends: List[List[List[int]]] = []
    for token, compiled in zip(form.tokens, form._compiled):
        if compiled is None:
            ends.append([])
            continue
        if compiled.pattern not in by_regex:
            by_regex[compiled.pattern] = [[k for k in range(j, n + 1) if compiled.fullmatch(line, j, k)]
                                          for j in range(n + 1)]
        every = by_regex[compiled.pattern]
        if token.greedy:  # the longest stretch from j, and none that a character before it would extend
            every = [e[-1:] if e and not (j and compiled.fullmatch(line, j - 1, e[-1])) else []
                     for j, e in enumerate(every)]
        ends.append(every)
    return ends


def align(form: Form, line: str) -> Tuple[float, List[Step]]:
    """The least number of edits that turn the form into a stretch of `line`, and the alignment's
    steps (the first edit as late as the least cost allows; whitespace placed as the form shows it). What is missing after the line's end
    counts half: a line cut short is nearer the form than one that says something else there
    (else "Sent at: 1.5" would be read as a missing Sent at value and 1.5 the Received at one)."""
    tokens, n, m = form.tokens, len(line), len(form.tokens)
    unit = n + 1
    edit, tail = EDIT * unit, TAIL * unit
    ends = _ends(form, line)
    # cost[i][j]: the least cost of aligning tokens[i:] with a start of line[j:] (the rest is free)
    cost = [[INF] * (n + 1) for _ in range(m + 1)]
    for j in range(n + 1):
        cost[m][j] = n - j
    for i in range(m - 1, -1, -1):
        token, row, below = tokens[i], cost[i], cost[i + 1]
        for j in range(n, -1, -1):
            best = below[j] + (edit if j < n else tail)  # the token missing
            if j < n:
                best = min(best, row[j + 1] + edit)  # an extra character of the line
                if token.literal:
                    best = min(best, below[j + 1] + (0 if _same(token, line[j]) else edit))
            if not token.literal:
                best = min([best] + [below[k] for k in ends[i][j]])
            row[j] = best
    total = min(cost[0])
    start = cost[0].index(total)
    steps: List[Step] = []
    i, j = 0, start
    while i < m:
        token, here = tokens[i], cost[i][j]
        if token.literal and j < n and _same(token, line[j]) and cost[i + 1][j + 1] == here:
            steps.append((MATCH, i, i + 1, j, j + 1))
            i, j = i + 1, j + 1
            continue
        if not token.literal:
            fits = [k for k in ends[i][j] if cost[i + 1][k] == here]
            if fits:
                # optional whitespace shown as nothing takes the least it can, that shown as a space
                # the most, a value the most but trailing whitespace: "line Sent", ',' missing after
                # "line"; "Message: , Sent", the text missing after "Message: "
                k = min(fits) if not token.display else max(fits)
                while token.display.strip() and k - 1 in fits and line[k - 1].isspace():
                    k -= 1
                steps.append((CONSUME, i, i + 1, j, k))
                i, j = i + 1, k
                continue
        # whitespace of the line where the form has a character: that character is missing
        missing = cost[i + 1][j] + (edit if j < n else tail) == here
        if missing and j < n and line[j].isspace():
            steps.append((MISSING, i, i + 1, j, j))
            i += 1
        elif token.literal and j < n and cost[i + 1][j + 1] + edit == here:
            steps.append((SUBSTITUTE, i, i + 1, j, j + 1))
            i, j = i + 1, j + 1
        elif j < n and cost[i][j + 1] + edit == here:
            steps.append((EXTRA, i, i, j, j + 1))
            j += 1
        else:
            steps.append((MISSING, i, i + 1, j, j))
            i += 1
    return (total // unit) / EDIT, steps  # in edits (the characters left over count for nothing)


def _edited(step: Step) -> bool:
    return step[0] not in (MATCH, CONSUME)


def difference(form: Form, line: str, settle: int = 2) -> Optional[Difference]:
    """Where `line` departs from `form` (None when it fits): the first run of edits, up to `settle`
    matched characters in a row, widened to whole words where it changes letters or digits."""
    if re.search(form.pattern, line, re.IGNORECASE | re.DOTALL):
        return None  # the check's own pattern finds it: nothing to point at
    total, steps = align(form, line)
    first = next((n for n, s in enumerate(steps) if _edited(s)), None)
    if first is None:  # (an alignment without edits is a match of the pattern, found above)
        return None
    last, matched = first, 0
    for n in range(first + 1, len(steps)):
        if _edited(steps[n]):
            last, matched = n, 0
        elif steps[n][4] > steps[n][3]:  # what matched some of the line (not whitespace left out)
            matched += 1
            if matched >= settle:
                break
    run = steps[first:last + 1]
    j0, j1 = run[0][3], run[-1][4]
    i0, i1 = run[0][1], run[-1][2]
    printed, expected = line[j0:j1], "".join(t.display for t in form.tokens[i0:i1])

    def word(n: int) -> bool:  # step n matches a letter or digit
        return 0 <= n < len(steps) and steps[n][0] == MATCH and line[steps[n][3]].isalnum()
    if any(c.isalnum() for c in printed + expected) or (word(first - 1) and word(last + 1)):  # show whole words
        left = first
        while word(left - 1):
            left -= 1
        right = last
        while word(right + 1):
            right += 1
        printed = line[steps[left][3]:steps[right][4]]
        expected = "".join(t.display for t in form.tokens[steps[left][1]:steps[right][2]])
    position = run[0][3]
    return Difference(line, position, printed, expected, line[:position], total)


def closest(lines: Iterable[str], form: Form, within: Optional[float] = None, last: int = 200,
            width: int = 300, shortlist: int = 5) -> Optional[Difference]:
    """The line of `lines` (the last `last` of them, each cut to `width` characters) that comes
    closest to `form`, and where it departs; None when none comes within `within` edits (default:
    a third of the form's literal characters; a line that shares none of them costs half) or one
    fits the form."""
    order = {line[:width]: n for n, line in enumerate(list(lines)[-last:]) if line.strip()}  # the last place
    within = form.literal_count() / 3 if within is None else within
    rough = form.display.casefold()
    # the alignment is quadratic in a line's length: a quick likeness picks the lines worth it
    ranked = sorted(order, key=lambda s: difflib.SequenceMatcher(None, s.casefold(), rough, autojunk=False).ratio(),
                    reverse=True)[:shortlist]
    best: Optional[Difference] = None
    for line in ranked:
        diff = difference(form, line)
        if diff is None:
            return None  # a line fits: nothing to point at
        if best is None or (diff.cost, -order[line]) < (best.cost, -order[best.line]):  # ties: the later line
            best = diff
    return best if best is not None and best.cost <= within else None


def _short(text: str, limit: int = 40) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."


def describe(diff: Difference) -> str:
    """The difference in words: "the closest line printed, '<the line>', differs from the text's
    form at character 54: 'Recieved' where the text has 'Received'" (or "',' missing after ...",
    "an extra ... after ...", "the line ends where the text goes on with ...")."""
    before = diff.before.rstrip()
    if len(before) > 24:  # its last whole words
        before = before[-24:] if before[-25].isspace() else before[-24:].split(" ", 1)[-1]
    if diff.printed and diff.expected:
        what = "%r where the text has %r" % (_short(diff.printed), _short(diff.expected))
    elif diff.expected and diff.position >= len(diff.line.rstrip()):
        what = "the line ends where the text goes on with %r" % _short(diff.expected)
    elif diff.expected:
        what = "%r missing%s" % (_short(diff.expected), " after %r" % before if before else " at the start")
    else:
        what = "an extra %r%s" % (_short(diff.printed), " after %r" % before if before else " at the start")
    return "the closest line printed, %r, differs from the text's form at character %d: %s" % (
        _short(diff.line, 160), diff.position + 1, what)


def closest_words(output: str, form: Form) -> str:
    """'; ' and the closest line of `output` with its difference from `form`, or '' when no line
    comes close (for the end of a failure's sentence)."""
    diff = closest(output.splitlines(), form)
    return "; " + describe(diff) if diff else ""
