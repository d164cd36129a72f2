"""Mutation sites in C++ sources, CMakeLists.txt and launch files, found by regular expressions.

These files are not parsed: each site is a pattern narrow enough to name one ROS call, tag or
list entry, and the edit touches only the matched text. Each function takes a file's text and
returns its mutated texts, one per site.
"""
from __future__ import annotations

import re
from typing import Callable, List, Match, Pattern

from course_lint.python_sites import RENAME_SUFFIX

CPP_NAMED = re.compile(r'\b(?:advertise|subscribe|advertiseService|serviceClient)\s*(?:<[^<>()]*(?:<[^<>()]*>)?[^<>()]*>)?'
                       r'\s*\(\s*"(?:[^"\\\n]|\\.)*(")')
CPP_RATE = re.compile(r"\bros::Rate\s*(?:\w+\s*)?[({]([^(){}]*(?:\([^()]*\))?[^(){}]*)[)}]")
CPP_SPIN = re.compile(r"\bros::spin\s*\(\s*\)\s*;")
CPP_PUBLISH = re.compile(r"(?:\.|->)\s*publish\s*\(")
CPP_XY = re.compile(r"(?:\.|->)\s*([xy])\b(?!\s*\()")
CMAKE_FILES = re.compile(r"\badd_(?:message|service|action)_files\s*\(([^)]*)\)", re.IGNORECASE)
CMAKE_KEYWORDS = frozenset({"DIRECTORY", "FILES", "NOINSTALL"})
XML_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)
REMAP_TAG = re.compile(r"<remap\b[^>]*>")
PARAM_TAG = re.compile(r"<param\b[^>]*>")
# A launch file's node, with no body (`<node .../>`) or with one (its params, remaps), up to its end tag.
NODE_TAG = re.compile(r"<node\b(?:[^>]*/>|[^>]*[^/]>.*?</node\s*>)", re.DOTALL)
TO_ATTR = re.compile(r"""\bto\s*=\s*(["'])(.*?)\1""", re.DOTALL)
VALUE_ATTR = re.compile(r"""\bvalue\s*=\s*(["'])(.*?)\1""", re.DOTALL)


def each(pattern: Pattern, text: str, edit: Callable[[Match], str]) -> List[str]:
    return [edit(m) for m in pattern.finditer(text)]


def cpp_topic_renamed(text: str) -> List[str]:
    return each(CPP_NAMED, text, lambda m: text[:m.start(1)] + RENAME_SUFFIX + text[m.start(1):])


def cpp_rate_div10(text: str) -> List[str]:
    return [text[:m.start(1)] + "(%s) / 10.0" % m.group(1) + text[m.end(1):]
            for m in CPP_RATE.finditer(text) if m.group(1).strip()]


def cpp_no_spin(text: str) -> List[str]:
    return each(CPP_SPIN, text, lambda m: text[:m.start()] + "/* course-lint: no spin */;" + text[m.end():])


def statement_end(text: str, open_paren: int) -> int:
    """The offset after the `;` closing a call whose `(` is at open_paren, or -1."""
    depth = 0
    for i in range(open_paren, len(text)):
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        if depth == 0:
            rest = re.match(r"\s*;", text[i + 1:])
            return i + 1 + rest.end() if rest else -1
    return -1


def cpp_exit_after_one(text: str) -> List[str]:
    ends = [statement_end(text, m.end() - 1) for m in CPP_PUBLISH.finditer(text)]
    return [text[:e] + " std::exit(0);  // course-lint: exit after one message" + text[e:] for e in ends if e > 0]


def cpp_publish_removed(text: str) -> List[str]:
    found = []
    for m in CPP_PUBLISH.finditer(text):
        end = statement_end(text, m.end() - 1)
        start = text.rfind("\n", 0, m.start()) + 1
        if end > 0:
            indent = len(text[start:]) - len(text[start:].lstrip())
            found.append(text[:start + indent] + ";  // course-lint: publish removed" + text[end:])
    return found


def cpp_swap_xy(text: str) -> List[str]:
    by_line = {}
    for m in CPP_XY.finditer(text):
        by_line.setdefault(text.count("\n", 0, m.start()), []).append(m)
    found = []
    for line in sorted(by_line):
        chars = list(text)
        for m in by_line[line]:
            chars[m.start(1)] = "y" if m.group(1) == "x" else "x"
        found.append("".join(chars))
    return found


def without(text: str, start: int, end: int) -> str:
    """The text less [start, end) and the blanks before it; less its whole line when alone on it."""
    line_start = text.rfind("\n", 0, start) + 1
    line_end = text.find("\n", end)
    line_end = len(text) if line_end < 0 else line_end
    if not text[line_start:start].strip() and not text[end:line_end].strip() and line_end < len(text):
        return text[:line_start] + text[line_end + 1:]
    return text[:start].rstrip(" \t") + text[end:]


def msg_left_out(text: str) -> List[str]:
    """One interface file left out of an add_message/service/action_files FILES list."""
    found = []
    for call in CMAKE_FILES.finditer(text):
        in_files = False
        for token in re.finditer(r"\S+", call.group(1)):
            word = token.group()
            if word.upper() in CMAKE_KEYWORDS:
                in_files = word.upper() == "FILES"
            elif in_files and not word.startswith("#"):
                found.append(without(text, call.start(1) + token.start(), call.start(1) + token.end()))
    return found


def outside_comments(pattern: Pattern, text: str) -> List[Match]:
    comments = [m.span() for m in XML_COMMENT.finditer(text)]
    return [m for m in pattern.finditer(text) if not any(a <= m.start() < b for a, b in comments)]


def remap_renamed(text: str) -> List[str]:
    found = []
    for tag in outside_comments(REMAP_TAG, text):
        to = TO_ATTR.search(tag.group())
        if to:
            at = tag.start() + to.end(2)
            found.append(text[:at] + RENAME_SUFFIX + text[at:])
    return found


def changed_value(value: str) -> str:
    """Another value of the same kind: a number moved, a boolean flipped, a word suffixed."""
    lower = value.strip().lower()
    if lower in ("true", "false"):
        return "false" if lower == "true" else "true"
    try:
        number = int(value)
        return str(number + 100 if number < 100 else number - 100)
    except ValueError:
        pass
    try:
        number = float(value)
        return repr(number * 2 if number else 1.0)
    except ValueError:
        return value + RENAME_SUFFIX


def param_changed(text: str) -> List[str]:
    found = []
    for tag in outside_comments(PARAM_TAG, text):
        value = VALUE_ATTR.search(tag.group())
        if value:
            start, end = tag.start() + value.start(2), tag.start() + value.end(2)
            found.append(text[:start] + changed_value(value.group(2)) + text[end:])
    return found


def node_left_out(text: str) -> List[str]:
    """One `<node>` of a launch file left out (its params and remaps with it): a node forgotten."""
    return [without(text, tag.start(), tag.end()) for tag in outside_comments(NODE_TAG, text)]
