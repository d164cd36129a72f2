"""The class list: who may log in to the hub, and who of them are TAs (the hub's admins).

A CSV file with a header line naming at least `username`; `role` is `student` (the default when
the column or the cell is empty) or `ta`; other columns (a name, an e-mail) are kept for the
course's own use and ignored here:

    username,role,name
    alice,student,Alice A.
    tom,ta,Tom the TA

A user name becomes the name of the student's container, network, folders and web address
(course_hub.names), so it must be short, lower case and plain: a letter, then letters, digits and
single `-` or `_` between them, at most 32 characters (JupyterHub lower-cases what a user types at
the login, so `Alice` logs in as `alice`). `_` and `-` are one on the host (`jean_luc` lives in
`users/jean-luc`), so a list naming both `jean_luc` and `jean-luc` is refused at the second. Any
other line is refused with its line number: a class list with one bad line does not half-load.
"""
from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from typing import Dict, FrozenSet, List

from course_hub import names

ROLES = ("student", "ta")
DEFAULT_ROLE = "student"


class ClassListError(ValueError):
    """The class list cannot be used; the message says where and why."""


@dataclass(frozen=True)
class ClassList:
    """Who may log in (`users`), and the TAs among them (`admins`); `roles` maps each to its role."""

    roles: Dict[str, str] = field(default_factory=dict)

    @property
    def users(self) -> FrozenSet[str]:
        return frozenset(self.roles)

    @property
    def admins(self) -> FrozenSet[str]:
        return frozenset(u for u, role in self.roles.items() if role == "ta")

    @property
    def students(self) -> List[str]:
        return sorted(u for u, role in self.roles.items() if role == "student")


def parse(text: str, source: str = "class list") -> ClassList:
    """The class list in `text` (CSV, see the module docstring); ClassListError naming `source`
    and the line of the first problem."""
    rows = csv.reader(io.StringIO(text.lstrip("\ufeff")))
    header: List[str] = []
    roles: Dict[str, str] = {}
    slugs: Dict[str, str] = {}
    for row in rows:
        line = rows.line_num
        if not any(cell.strip() for cell in row) or row[0].lstrip().startswith("#"):
            continue
        if not header:
            header = [cell.strip().lower() for cell in row]
            if "username" not in header:
                raise ClassListError("%s line %d: the header must name a `username` column (and may name `role`), "
                                     "got %s" % (source, line, ",".join(row)))
            continue
        cells = dict(zip(header, (cell.strip() for cell in row)))
        name = cells.get("username", "")
        role = (cells.get("role") or DEFAULT_ROLE).lower()
        try:
            word = names.slug(name)
        except ValueError:
            raise ClassListError("%s line %d: %r is no user name the hub can use (lower case: a letter, then "
                                 "letters, digits and single - or _ between them, at most 32)"
                                 % (source, line, name)) from None
        if role not in ROLES:
            raise ClassListError("%s line %d: role %r of %s must be one of %s" % (
                source, line, role, name, ", ".join(ROLES)))
        if name in roles:
            raise ClassListError("%s line %d: %s is listed twice" % (source, line, name))
        if word in slugs:
            raise ClassListError("%s line %d: %s and %s would share one folder and one address (users/%s): "
                                 "- and _ are one on the hub; give one of them another name"
                                 % (source, line, slugs[word], name, word))
        slugs[word] = name
        roles[name] = role
    if not roles:
        raise ClassListError("%s: no user in it (a header line `username,role`, then one line per user)" % source)
    return ClassList(roles)


def load(path: str) -> ClassList:
    """The class list in the file `path`."""
    try:
        with open(path, newline="", encoding="utf-8") as stream:
            return parse(stream.read(), path)
    except OSError as err:
        raise ClassListError("cannot read the class list %s: %s" % (path, err.strerror)) from None
