"""The Makefile's targets as make itself reads them: each has its line in `make help` (the text after
`## ` on the target's line), and .PHONY names only targets the Makefile defines. Pure and fast: make's
database (`make -pRrq`, which runs no recipe) and `make help`'s output; no build, no ROS."""
from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path
from typing import Dict, NamedTuple

ROOT = Path(__file__).resolve().parents[1]
# A file entry's first line in make's database: `name: prerequisites` (a variable would be `name :=`).
ENTRY = re.compile(r"^([^#\s:=][^:=]*?):(?![:=])\s*(.*)$")
HELP_LINE = re.compile(r"^  (\S+) +(\S.*)$")


class Entry(NamedTuple):
    prerequisites: str
    has_recipe: bool

    @property
    def defined(self) -> bool:
        """The Makefile defines it: a recipe or prerequisites of its own (.PHONY alone does neither)."""
        return self.has_recipe or bool(self.prerequisites)


def make(*args: str) -> subprocess.CompletedProcess:
    # Not the outer make's flags: `make test` runs this suite inside a recipe.
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "MAKEFILES")}
    return subprocess.run(["make", "--no-print-directory", "-C", str(ROOT), *args], env=env, stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60, check=False)


def database() -> Dict[str, Entry]:
    """Every file entry of make's database: name -> its prerequisites and whether it has a recipe.
    -q runs nothing (its exit code says whether the default goal is up to date, which is beside the point)."""
    text = make("-pRrq").stdout
    files = text.split("\n# Files\n", 1)[1].split("\n# files hash-table stats", 1)[0]
    entries = {}
    for paragraph in files.split("\n\n"):
        lines = paragraph.strip("\n").splitlines()
        if not lines or lines[0].startswith("# Not a target"):
            continue
        head = next((ENTRY.match(line) for line in lines if not line.startswith("#")), None)
        if head:
            entries[head.group(1)] = Entry(head.group(2).strip(),
                                           any(line.startswith("#  recipe to execute") for line in lines))
    return entries


def help_lines() -> Dict[str, str]:
    done = make("help")
    assert done.returncode == 0, done.stderr
    found = {}
    for line in done.stdout.splitlines()[1:]:
        m = HELP_LINE.match(line)
        assert m, "not a `  target  what it does` line: %r" % line
        found[m.group(1)] = m.group(2)
    return found


def test_every_target_has_its_line_in_make_help():
    targets = {name for name, entry in database().items() if entry.defined and not name.startswith(".")}
    assert {"help", "deps", "build", "demo", "test"} <= targets  # the database was read
    listed = help_lines()
    assert sorted(targets - set(listed)) == [], "targets without a `## ` line in `make help`"
    assert sorted(set(listed) - targets) == [], "`make help` lists what is no target"


def test_phony_names_only_targets_the_makefile_defines():
    entries = database()
    phony = entries[".PHONY"].prerequisites.split()
    assert "help" in phony
    assert [name for name in phony if not entries[name].defined] == []
