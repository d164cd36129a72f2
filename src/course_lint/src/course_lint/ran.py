"""What the reference's run of a milestone executed, measured, and which mutants it leaves `not run`.

course-lint grades a milestone's reference first, alone, with one more package beside it:
course_lint_probe (lay_out below), whose catkin environment hook only the student's processes of
that run get (the grader sources an overlay's devel/setup.bash for them alone, inside the
sandbox; its own side computes its paths). The hook sets:
- PYTHONPATH: the probe's site folder first, whose sitecustomize runs course_lint.probe in every
  Python process: coverage.py measures the lines it runs of the files under src/, and the files
  under src/ it opens are recorded (roslaunch reading launch files);
- LD_AUDIT: the probe's exec log (exec_log.c, built by the probe package), which the dynamic
  linker loads into every program started: which executables ran (a C++ node among them);
- COURSE_LINT_DATA, COURSE_LINT_SRC: where the records go, and the workspace's src/.
The grader itself is unchanged, and a real grading never meets the package. Once the reference
has passed, read() gathers the records from the reference's workspace (kept under the grader's
output, _work/<student>/ws) and not_run() tells, per mutant, whether the line it changes never
ran: such a mutant needs no grading.

Only what was measured counts: a kind of file whose measurement failed or is missing in this run
is graded (`Ran.python`, `Ran.programs` say why), and so is a file whose link to what ran cannot be
told (a C++ file no add_executable names, a line outside any statement). Pure but for reading
files: no ROS.
"""
from __future__ import annotations

import ast
import os
import shutil
from typing import Dict, FrozenSet, Iterable, List, NamedTuple, Optional, Set, Tuple

from course_lint import used_files
from course_lint.mutants import CMAKE, CPP, LAUNCH, PYTHON, Mutant, kind_of
from course_lint.probe import PACKAGE
DATA = "data"  # the records' folder in the probe package
SITE = "site"  # the folder put first on PYTHONPATH
PROBE_FILES = ("sitecustomize.py", "exec_log.c")  # from course_lint's probe/ folder
RECORD_SEPARATOR = "\x1f"  # between the words of an exec record's argv

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>%s</name>
  <version>0.0.0</version>
  <description>course-lint's probe: measures what the reference's lint run executed (docs/course_lint.md).</description>
  <maintainer email="course@example.org">course-lint</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
</package>
""" % PACKAGE

CMAKE_LISTS = """cmake_minimum_required(VERSION 3.0.2)
project(%s C)
find_package(catkin REQUIRED)
catkin_add_env_hooks(50.%s SHELLS sh DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/env-hooks)
catkin_package()
add_library(course_lint_exec_log MODULE exec_log.c)
""" % (PACKAGE, PACKAGE)

# configured by catkin into devel/etc/catkin/profile.d/, which devel/setup.sh sources. Only once the
# exec log is built: the build's own commands run in a snapshot of the environment taken before it
# (build/catkin_generated/setup_cached.sh), which then has none of this.
ENV_HOOK = """# course-lint's probe (course_lint.ran): only the reference's lint run has this package
if [ -f "@CATKIN_DEVEL_PREFIX@/lib/libcourse_lint_exec_log.so" ]; then
  export COURSE_LINT_DATA="@CMAKE_CURRENT_SOURCE_DIR@/%s"
  export COURSE_LINT_SRC="@CMAKE_SOURCE_DIR@"
  export PYTHONPATH="@CMAKE_CURRENT_SOURCE_DIR@/%s${PYTHONPATH:+:$PYTHONPATH}"
  export LD_AUDIT="@CATKIN_DEVEL_PREFIX@/lib/libcourse_lint_exec_log.so"
fi
""" % (DATA, SITE)


def probe_folder() -> str:
    """course_lint's probe/ folder (sitecustomize.py, exec_log.c): in the source tree (devel space)
    or the package's share folder (install space)."""
    import rospkg
    return os.path.join(rospkg.RosPack().get_path("course_lint"), "probe")


def lay_out(submission: str, files: Optional[str] = None) -> str:
    """The probe package in the submission folder `submission`, from the probe files in `files`
    (default: probe_folder()); its folder."""
    files = files or probe_folder()
    folder = os.path.join(submission, PACKAGE)
    shutil.rmtree(folder, ignore_errors=True)
    for sub in (DATA, SITE, "env-hooks"):
        os.makedirs(os.path.join(folder, sub))
    os.chmod(os.path.join(folder, DATA), 0o777)  # the sandbox user's processes write here (the grader
    # gives it the workspace when it switches users; this is for a grader that does not own it)
    for name, text in (("package.xml", PACKAGE_XML), ("CMakeLists.txt", CMAKE_LISTS),
                       (os.path.join("env-hooks", "50.%s.sh.in" % PACKAGE), ENV_HOOK)):
        with open(os.path.join(folder, name), "w") as f:
            f.write(text)
    shutil.copy(os.path.join(files, "sitecustomize.py"), os.path.join(folder, SITE, "sitecustomize.py"))
    shutil.copy(os.path.join(files, "exec_log.c"), os.path.join(folder, "exec_log.c"))
    return folder


def workspace(out: str, student: str) -> str:
    """The overlay workspace the grader built for `student` (kept under its output folder)."""
    from course_grader.class_outputs import WORK_DIR
    return os.path.join(out, WORK_DIR, student, "ws")


class Ran(NamedTuple):
    """What one run executed. Paths are relative to the workspace's src/ ("pkg/scripts/a.py")."""

    lines: Dict[str, FrozenSet[int]]  # Python file -> the lines coverage.py saw run
    opened: FrozenSet[str]  # files a Python process opened (launch files, by roslaunch)
    programs: FrozenSet[str]  # the programs started (real paths, from the exec log)
    python: str  # "" when Python's lines and opens were measured, else why they were not
    started: str  # "" when the exec log measured the programs started, else why it did not

    def notes(self) -> List[str]:
        return ["Python not measured (its mutants are graded): %s" % self.python] * bool(self.python) + \
               ["programs started not measured (C++ mutants are graded): %s" % self.started] * bool(self.started)


NOTHING = Ran({}, frozenset(), frozenset(), "no measurement", "no measurement")


def read(ws: str) -> Ran:
    """The records of the probe in the workspace `ws` (see the module docstring)."""
    folder = os.path.join(ws, "src", PACKAGE, DATA)
    src = os.path.realpath(os.path.join(ws, "src"))
    try:
        names = sorted(os.listdir(folder))
    except OSError as err:
        return NOTHING._replace(python="no records (%s)" % err, started="no records (%s)" % err)
    texts = []
    for name in names:
        try:
            with open(os.path.join(folder, name), encoding="utf-8", errors="surrogateescape") as f:
                texts.append((name, f.read()))
        except OSError:
            continue
    return parse(texts, src)


def _relative(path: str, src: str) -> Optional[str]:
    rel = os.path.relpath(path, src)
    return None if rel == os.pardir or rel.startswith(os.pardir + os.sep) or os.path.isabs(rel) else rel


def parse(texts: Iterable[Tuple[str, str]], src: str) -> Ran:
    """Ran from the record files' (name, text): `py.*` from course_lint.probe, `exec.*` from
    exec_log.c; `src` is the workspace's src/ as the run saw it (a real path)."""
    lines: Dict[str, Set[int]] = {}
    opened: Set[str] = set()
    programs: Set[str] = set()
    measured: Set[Tuple[str, str]] = set()  # (pid namespace, pid) of each Python process measured
    started_python: List[Tuple[str, str, str]] = []  # (namespace, pid, argv) of each Python interpreter started
    errors: List[str] = []
    execs = 0
    for name, text in texts:
        for record in text.split("\n"):
            words = record.split("\t")
            kind = words[0]
            if kind == "lines" and len(words) == 3:
                rel = _relative(words[1], src)
                if rel is not None:
                    lines.setdefault(rel, set()).update(int(n) for n in words[2].split() if n.isdigit())
            elif kind == "open" and len(words) == 2:
                rel = _relative(words[1], src)
                if rel is not None:
                    opened.add(rel)
            elif kind == "start" and len(words) == 5 and words[3] == "1":
                measured.add((words[1], words[2]))
            elif kind == "error" and len(words) >= 2:
                errors.append("\t".join(words[1:]))
            elif kind == "exec" and len(words) == 5:
                execs += 1
                programs.add(words[3])
                argv = words[4].split(RECORD_SEPARATOR)
                if os.path.basename(words[3]).startswith("python"):
                    started_python.append((words[1], words[2], " ".join(argv)))
    python = ""
    if errors:
        python = "coverage.py failed in a process of the run: %s" % errors[0]
    elif execs:
        missing = [(ns, pid, argv) for ns, pid, argv in started_python if (ns, pid) not in measured]
        if missing:
            python = "a Python process of the run left no record of its lines (pid %s: %s)" % missing[0][1:]
    elif not measured:
        python = "no Python process of the run was measured"
    started = "" if execs else "the run left no exec log (LD_AUDIT)"
    return Ran({k: frozenset(v) for k, v in lines.items()}, frozenset(opened), frozenset(programs), python, started)


def changed_lines(before: str, after: str) -> List[int]:
    """The lines of `before` (1-based) between what the two texts share at their start and at their
    end: those `after` replaces or deletes. Where it only inserts, the line just above the insertion,
    which runs right before what is inserted (line 1 at the top). A mutant changes one site; for one
    that changed two, the lines between are named too, so it is graded more often, never less."""
    old, new = before.splitlines(), after.splitlines()
    head = 0
    while head < min(len(old), len(new)) and old[head] == new[head]:
        head += 1
    tail = 0
    while tail < min(len(old), len(new)) - head and old[-1 - tail] == new[-1 - tail]:
        tail += 1
    if head == len(old) - tail:
        return [max(head, 1)]
    return list(range(head + 1, len(old) - tail + 1))


def statement_spans(source: str) -> List[Tuple[int, int]]:
    """(first, last) line of each statement of a Python source: a simple statement's every line; a
    compound statement's header (from its first decorator to the line before its body). A line
    event of coverage.py on any of them means the statement ran. ValueError when it does not parse."""
    try:
        tree = ast.parse(source)
    except (SyntaxError, ValueError) as err:
        raise ValueError(str(err)) from None
    spans = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.stmt):
            continue
        first = min([node.lineno] + [d.lineno for d in getattr(node, "decorator_list", [])])
        inner = [child.lineno for field in ("body", "orelse", "handlers", "finalbody", "cases")
                 for child in getattr(node, field, []) or [] if hasattr(child, "lineno")]
        last = max(node.lineno, min(inner) - 1) if inner else (node.end_lineno or node.lineno)
        spans.append((first, last))
    return spans


def statements_of(source: str, numbers: Iterable[int]) -> Optional[List[Tuple[int, int]]]:
    """The innermost statement span holding each line; None when a line lies in none (a comment,
    an `else:`) or the source does not parse: then whether it ran cannot be told."""
    try:
        spans = statement_spans(source)
    except ValueError:
        return None
    found = []
    for n in numbers:
        holding = [s for s in spans if s[0] <= n <= s[1]]
        if not holding:
            return None
        found.append(min(holding, key=lambda s: s[1] - s[0]))
    return found


def not_run(mutant: Mutant, reference: str, ran: Ran, package: str, cmake: str = "") -> str:
    """Why `mutant` (of a file whose reference text is `reference`, in the package named `package`,
    whose CMakeLists.txt is `cmake`) needs no grading: what it changes never ran in the run `ran`;
    "" when it may have run, or that cannot be told."""
    where = "%s/%s" % (mutant.package, mutant.path)
    kind = kind_of(mutant.path, reference)
    if kind == PYTHON:
        if ran.python:
            return ""
        run = ran.lines.get(where, frozenset())
        if not run:
            return "%s never ran" % os.path.basename(mutant.path)
        spans = statements_of(reference, changed_lines(reference, mutant.text))
        if not spans or any(run & set(range(first, last + 1)) for first, last in spans):
            return ""
        return "line %d never ran" % spans[0][0]
    if kind == LAUNCH:
        if ran.python or where in ran.opened:
            return ""
        return "%s was never launched" % os.path.basename(mutant.path)
    if kind == CPP:
        return _cpp_not_run(mutant, ran, package, cmake)
    return ""  # CMakeLists.txt: the build ran (CMAKE), and anything else is graded


def _cpp_not_run(mutant: Mutant, ran: Ran, package: str, cmake: str) -> str:
    """A C++ file runs when an executable built from it starts (devel/lib/PACKAGE/NAME, NAME an
    add_executable of CMakeLists.txt): not run when every executable listing it never started, and
    every program of the package that started is one of them by name."""
    if ran.started:
        return ""
    built = used_files.executables(cmake)
    mine = sorted(name for name, sources in built.items() if os.path.normpath(mutant.path) in sources)
    if not mine:
        return ""  # a header, or a library's source: which executables use it is not told here
    folder = os.sep + os.path.join("devel", "lib", package) + os.sep
    started = {os.path.basename(p) for p in ran.programs if folder in p}
    if started & set(mine) or started - set(built):
        return ""
    return "%s never started" % " or ".join(mine)


def kinds_measured(ran: Ran) -> Dict[str, str]:
    """Per kind of file, how its mutants' `not run` was told: "measured", or why it was not (then
    they are all graded)."""
    return {PYTHON: ran.python or "measured", LAUNCH: ran.python or "measured",
            CPP: ran.started or "measured", CMAKE: "not measured: the build always runs"}
