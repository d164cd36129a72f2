"""Mutation sites in a Python node's source, found with the `ast` module.

Each function takes a file's text and returns the file's mutated texts, one per site. Edits are
made on the text at the nodes' positions, so the rest of the file keeps its formatting and
comments; a mutant the student could have written, not a reprinted tree. A text that does not
parse has no sites (the caller notes it).
"""
from __future__ import annotations

import ast
import re
from typing import Callable, Iterator, List, Optional, Tuple

# Calls that register a name on the ROS graph: their first argument is a topic, service or action.
REGISTERING = frozenset({"Publisher", "Subscriber", "Service", "ServiceProxy", "SimpleActionServer",
                         "SimpleActionClient", "ActionServer", "ActionClient"})
RENAME_SUFFIX = "_mutant"
# A message class every ROS install has, loaded without an import line of the node's own.
OTHER_TYPE = '__import__("std_msgs.msg").msg.%s'
# Calls whose arguments are only shown: a pose swapped inside them changes no behaviour.
SHOWING = frozenset({"print", "loginfo", "logwarn", "logerr", "logdebug", "logfatal", "loginfo_throttle",
                     "logwarn_throttle", "loginfo_once"})
EXIT_NOW = '__import__("os")._exit(0)  # course-lint: exit after one message'
NEWLINE = re.compile(r"\r\n|\r|\n")


class Source:
    """A Python file's text and tree, with the nodes' spans as offsets into the text."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.tree = ast.parse(text)
        self.starts = [0] + [m.end() for m in NEWLINE.finditer(text)]

    def offset(self, lineno: int, col_bytes: int) -> int:
        start = self.starts[lineno - 1]
        end = self.starts[lineno] if lineno < len(self.starts) else len(self.text)
        line = self.text[start:end]
        return start + len(line.encode("utf-8")[:col_bytes].decode("utf-8", "ignore"))

    def span(self, node: ast.AST) -> Tuple[int, int]:
        return (self.offset(node.lineno, node.col_offset), self.offset(node.end_lineno, node.end_col_offset))

    def segment(self, node: ast.AST) -> str:
        start, end = self.span(node)
        return self.text[start:end]

    def replaced(self, node: ast.AST, new: str) -> str:
        start, end = self.span(node)
        return self.text[:start] + new + self.text[end:]

    def line_end(self, lineno: int) -> int:
        """The offset of line `lineno`'s line break (or the text's end)."""
        match = NEWLINE.search(self.text, self.starts[lineno - 1])
        return match.start() if match else len(self.text)

    def nodes(self, kind: type) -> Iterator:
        return (n for n in ast.walk(self.tree) if isinstance(n, kind))


def parse(text: str) -> Optional[Source]:
    try:
        return Source(text)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None


def on_source(sites: Callable[[Source], List[str]]) -> Callable[[str], List[str]]:
    """An operator on a file's text from one on its parsed source: no sites when it does not parse."""
    def on_text(text: str) -> List[str]:
        src = parse(text)
        return sites(src) if src is not None else []
    on_text.__name__, on_text.__doc__ = sites.__name__, sites.__doc__
    return on_text


def callee(call: ast.Call) -> str:
    """`rospy.Publisher(...)` -> "Publisher", `spin()` -> "spin", anything else -> ""."""
    func = call.func
    return func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""


def argument(call: ast.Call, index: int, keyword: str) -> Optional[ast.expr]:
    if len(call.args) > index and not isinstance(call.args[index], ast.Starred):
        return call.args[index]
    return next((k.value for k in call.keywords if k.arg == keyword), None)


def calls(src: Source, *names: str) -> List[ast.Call]:
    return sorted((c for c in src.nodes(ast.Call) if callee(c) in names), key=lambda c: (c.lineno, c.col_offset))


def string_root(src: Source, node: ast.expr) -> Optional[ast.expr]:
    """The string literal a name argument is made from: the literal, a %-format's or .format's
    string, or the module-level constant a bare name stands for."""
    if isinstance(node, ast.JoinedStr) or (isinstance(node, ast.Constant) and isinstance(node.value, str)):
        return node
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mod):
        return string_root(src, node.left)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "format":
        return string_root(src, node.func.value)
    if isinstance(node, ast.Name):
        for stmt in src.tree.body:
            if isinstance(stmt, ast.Assign) and [getattr(t, "id", None) for t in stmt.targets] == [node.id]:
                return string_root(src, stmt.value)
    return None


def suffixed_literal(segment: str, suffix: str) -> Optional[str]:
    """A string literal's source with `suffix` added before its closing quote(s)."""
    if not segment or segment[-1] not in "'\"":
        return None
    quotes = 3 if segment.endswith(segment[-1] * 3) and len(segment) >= 6 else 1
    return segment[:-quotes] + suffix + segment[-quotes:]


@on_source
def topic_renamed(src: Source) -> List[str]:
    found = []
    for call in calls(src, *REGISTERING):
        name = argument(call, 0, "name")
        root = string_root(src, name) if name is not None else None
        new = suffixed_literal(src.segment(root), RENAME_SUFFIX) if root is not None else None
        if new is not None:
            found.append(src.replaced(root, new))
    return found


@on_source
def type_changed(src: Source) -> List[str]:
    found = []
    for call in calls(src, "Publisher", "Subscriber"):
        data_class = argument(call, 1, "data_class")
        if data_class is not None:
            other = "String" if src.segment(data_class).endswith("Empty") else "Empty"
            found.append(src.replaced(data_class, OTHER_TYPE % other))
    return found


def statement_calls(src: Source, *names: str) -> List[ast.Expr]:
    """Statements that are one call of these names, e.g. `pub.publish(msg)`, `rospy.spin()`."""
    return sorted((s for s in src.nodes(ast.Expr) if isinstance(s.value, ast.Call) and callee(s.value) in names),
                  key=lambda s: (s.lineno, s.col_offset))


@on_source
def exit_after_one(src: Source) -> List[str]:
    """`os._exit(0)` on a line of its own right after each `.publish(...)` statement that starts its
    line and ends it (but for a comment): the node sends one message there and is gone."""
    found = []
    for stmt in statement_calls(src, "publish"):
        start, end = src.span(stmt)
        text = src.text
        indent = text[src.starts[stmt.lineno - 1]:start]
        line_end = src.line_end(stmt.end_lineno)
        rest = text[end:line_end].strip()
        if indent.strip() or (rest and not rest.startswith("#")):
            continue
        newline = NEWLINE.search(text).group() if NEWLINE.search(text) else "\n"
        found.append(text[:line_end] + newline + indent + EXIT_NOW + text[line_end:])
    return found


@on_source
def publish_removed(src: Source) -> List[str]:
    return [src.replaced(stmt, "pass") for stmt in statement_calls(src, "publish")]


@on_source
def no_spin(src: Source) -> List[str]:
    return [src.replaced(stmt, "pass") for stmt in statement_calls(src, "spin")]


def number(node: ast.expr) -> Optional[float]:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return node.value
    return None


@on_source
def rate_div10(src: Source) -> List[str]:
    found = []
    for call in calls(src, "Rate"):
        hz = argument(call, 0, "hz")
        if hz is not None:
            value = number(hz)
            found.append(src.replaced(hz, "%r" % (value / 10) if value is not None else "(%s) / 10" % src.segment(hz)))
    return found


@on_source
def swap_xy(src: Source) -> List[str]:
    """Per line, every `.x` becomes `.y` and every `.y` `.x` (a pose read or written crosswise).
    In a node that acts over ROS (publishes, offers or calls a service) not inside a print or log
    call, where a swap changes nothing the node does; a node that only prints keeps those."""
    acts = any(calls(src, "Publisher", "Service", "ServiceProxy"))
    shown = [src.span(c) for c in src.nodes(ast.Call) if acts and callee(c) in SHOWING]
    by_line = {}
    for attr in src.nodes(ast.Attribute):
        end = src.span(attr)[1]
        if attr.attr in ("x", "y") and not any(a <= end <= b for a, b in shown):
            by_line.setdefault(attr.end_lineno, []).append(attr)
    found = []
    for line in sorted(by_line):
        chars = list(src.text)
        for attr in by_line[line]:
            chars[src.span(attr)[1] - 1] = "y" if attr.attr == "x" else "x"
        found.append("".join(chars))
    return found


def is_pen_call(name: str) -> bool:
    lower = name.lower()
    return "setpen" in lower or "pen" in lower.split("_")


def inverted(src: Source, node: ast.expr) -> str:
    value = number(node)
    return "%r" % (255 - value) if value is not None else "255 - (%s)" % src.segment(node)


@on_source
def pen_off(src: Source) -> List[str]:
    """A set_pen call's r, g, b each turned to 255 minus itself: another colour."""
    found = []
    for call in sorted((c for c in src.nodes(ast.Call) if is_pen_call(callee(c))), key=lambda c: c.lineno):
        channels = [a for a in (argument(call, i, k) for i, k in enumerate("rgb")) if a is not None]
        if not channels:
            continue
        new = src.text
        for node in sorted(channels, key=lambda n: src.span(n), reverse=True):
            start, end = src.span(node)
            new = new[:start] + inverted(src, node) + new[end:]
        found.append(new)
    return found


@on_source
def param_ignored(src: Source) -> List[str]:
    """`rospy.get_param(name, default)` -> `(default)`: the node runs on its default."""
    found = []
    for call in calls(src, "get_param"):
        default = argument(call, 1, "default")
        if default is not None:
            found.append(src.replaced(call, "(%s)" % src.segment(default)))
    return found


def handler_names(src: Source) -> List[str]:
    names = []
    for call in calls(src, "Service"):
        handler = argument(call, 2, "handler")
        if isinstance(handler, ast.Name):
            names.append(handler.id)
        elif isinstance(handler, ast.Attribute):
            names.append(handler.attr)
    return names


def wrong_answer(src: Source, value: ast.expr) -> Optional[str]:
    """A response built without its values (zeros, empty strings), or the value's empty kind."""
    if isinstance(value, ast.Call) and callee(value).endswith("Response"):
        return "%s()" % src.segment(value.func) if value.args or value.keywords else None
    return "type(%s)()" % src.segment(value)


@on_source
def service_wrong(src: Source) -> List[str]:
    """Each `return X` of a function registered with rospy.Service answers a wrong value."""
    names = set(handler_names(src))
    found = []
    for func in src.nodes((ast.FunctionDef, ast.AsyncFunctionDef)):
        if func.name not in names:
            continue
        for ret in (n for n in ast.walk(func) if isinstance(n, ast.Return) and n.value is not None):
            new = wrong_answer(src, ret.value)
            if new is not None:
                found.append(src.replaced(ret.value, new))
    return found
