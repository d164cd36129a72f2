"""Scripts rosrun cannot start, or Python 3 cannot run, said in words a student can act on.

One detector for the whole course: the checks append its sentences to a failure (a student
running `rostest` alone sees them) and the grader adds the ones a check did not already say.
The mistakes real students make most, each found from their files (`script_problems`) or from
what their process printed (`output_problems`), never guessed from the milestone:
- a `#!` script handed in without its executable bit (the texts' `chmod +x` step), unless
  `catkin_install_python` lists it: catkin's devel space relays it then, and rosrun starts it;
- a `#!` line saved with Windows line endings (`/usr/bin/env: 'python3\r'`);
- an executable Python script with no `#!` line at all: rosrun runs it with `sh`, which
  prints `import: not found` and `Syntax error: "(" unexpected`;
- Python 2, from the Kinetic and Melodic tutorials most public code still follows: the `print`
  statement and `except X, e` (a SyntaxError before anything runs), `raw_input` (a NameError when
  reached), and `/` between integers, which gives a float in Python 3 (a TypeError where an
  integer was needed);
- `#!/usr/bin/env python` where no `python` is on PATH (the course's environment has one: its
  venv's, Python 3, so the course accepts that line; a machine without it prints
  `/usr/bin/env: 'python': No such file or directory`).
Pure file and text reading.
"""
from __future__ import annotations

import os
import re
from typing import Iterator, List, Set, Tuple

from course_format import causes

# Build products and tool folders: never a student's script.
SKIPPED_DIRS = {"build", "devel", "install", "logs", ".git", "__pycache__", ".catkin_tools", "__MACOSX"}
# Where a package's nodes are looked for: everywhere, as rosrun does (`find -L <package>` for an
# executable file of that name, its own build/ left out), so nodes kept in msg/, srv/, action/ or
# cfg/ count; but never in these folders: the build products and tool folders above, CMake's, and
# the package's tests (a test's helper node, started by a check, would be taken for the student's).
NOT_NODE_DIRS = frozenset(SKIPPED_DIRS | {"CMakeFiles", "test", "tests"})
# Larger files are data, not scripts.
MAX_SCRIPT_BYTES = 1024 * 1024


def _first_line(path: str) -> bytes:
    try:
        if not os.path.isfile(path) or os.path.getsize(path) > MAX_SCRIPT_BYTES:
            return b""
        with open(path, "rb") as f:
            return f.readline(512)
    except OSError:
        return b""


PYTHON3_FORM = "Noetic runs Python 3"
NO_SHEBANG = ("%s has no #! line, so rosrun runs it with sh (hence `import: not found` and `Syntax error`): "
              "make its first line #!/usr/bin/env python3")


def python2_problem(source: bytes, rel: str) -> str:
    """A sentence when `source` is Python 2 that Python 3 refuses to compile, else ""."""
    try:
        compile(source, rel, "exec", dont_inherit=True)
        return ""
    except SyntaxError as err:
        line = (err.text or "").strip()
        where = "%s line %s" % (rel, err.lineno)
        if "Missing parentheses in call to 'print'" in str(err.msg) or re.match(r"print\s+[^\s(=]", line):
            return causes.finding("python2", "%s: `%s` is Python 2's print statement; %s: write print(...)"
                                  % (where, line[:60], PYTHON3_FORM))
        if re.match(r"except\s+[\w.]+\s*,\s*\w+\s*:", line):
            exc, name = re.match(r"except\s+([\w.]+)\s*,\s*(\w+)", line).groups()
            return causes.finding("python2", "%s: `%s` is Python 2; %s: write `except %s as %s:`"
                                  % (where, line[:60], PYTHON3_FORM, exc, name))
        return ""
    except (ValueError, TypeError):  # a NUL byte: not Python source
        return ""


def _source(path: str) -> bytes:
    try:
        if os.path.getsize(path) > MAX_SCRIPT_BYTES:
            return b""
        with open(path, "rb") as f:
            return f.read()
    except OSError:
        return b""


def node_folders(root: str) -> Iterator[Tuple[str, List[str]]]:
    """(folder, its file names) of every folder under `root` (a package, or its devel/lib folder)
    that may hold a node of the student's, in name order: NOT_NODE_DIRS and hidden folders are left
    out. The one rule for the course's checks (course_milestones.discovery) and script_problems."""
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in NOT_NODE_DIRS and not d.startswith("."))
        yield folder, sorted(files)


# catkin_install_python(PROGRAMS a.py b.py DESTINATION ...) in a CMakeLists.txt (comments removed first)
_INSTALL_PYTHON = re.compile(r"\bcatkin_install_python\s*\(\s*PROGRAMS\b(.*?)(?:\bDESTINATION\b|\))",
                             re.DOTALL | re.IGNORECASE)
_SOURCE_DIR = re.compile(r"^\$\{(?:CMAKE_CURRENT_SOURCE_DIR|PROJECT_SOURCE_DIR)\}/")


def relayed_scripts(package_dir: str) -> Set[str]:
    """The scripts the package's CMakeLists.txt lists in catkin_install_python, as paths from the
    package's folder. catkin's devel space makes a relay for each (devel/lib/PKG/NAME, executable,
    running the source file), and its install space installs each executable: rosrun starts them
    with or without their own executable bit."""
    try:
        with open(os.path.join(package_dir, "CMakeLists.txt"), errors="replace") as f:
            text = re.sub(r"#[^\n]*", "", f.read(MAX_SCRIPT_BYTES))
    except OSError:
        return set()
    words = [w.strip('"') for m in _INSTALL_PYTHON.finditer(text) for w in m.group(1).split()]
    return {os.path.normpath(_SOURCE_DIR.sub("", w)) for w in words if w and "${" not in _SOURCE_DIR.sub("", w)}


def script_problems(package_dir: str) -> List[str]:
    """One sentence per problem: a #! line without the executable bit (unless catkin_install_python
    lists the script: relayed_scripts), a #! line ending in a carriage return, an executable .py
    file without a #! line, Python 2 that Python 3 cannot compile, in the folders where the checks
    look for nodes (node_folders). Paths are given from the package's name down
    (chatter/scripts/talker.py)."""
    problems = []
    relayed = relayed_scripts(package_dir)
    for folder, files in node_folders(package_dir):
        for name in files:
            path = os.path.join(folder, name)
            first = _first_line(path)
            rel = os.path.relpath(path, os.path.dirname(package_dir))
            if name.endswith(".py") and os.path.isfile(path):
                old = python2_problem(_source(path), rel)
                if old:
                    problems.append(old)
                if not first.startswith(b"#!") and os.access(path, os.X_OK):
                    problems.append(causes.finding("no_shebang", NO_SHEBANG % rel))
            if not first.startswith(b"#!"):
                continue
            if not os.access(path, os.X_OK) and os.path.relpath(path, package_dir) not in relayed:
                problems.append(causes.finding(
                    "not_executable", "%s starts with #! but is not executable, so rosrun cannot start it "
                                      "(chmod +x %s, and keep the bit in what you hand in)" % (rel, name)))
            if first.rstrip(b"\n").endswith(b"\r"):
                problems.append(causes.finding(
                    "windows_line_endings", "%s has Windows line endings: its #! line asks for '%s\\r', which does not "
                                "exist (convert it to Unix line endings, e.g. dos2unix %s)"
                                % (rel, (first[2:].decode(errors="replace").split() or ["?"])[-1], name)))
    return problems


# What a process printed -> the sentence naming its cause. Each pattern is the interpreter's own
# words for one mistake; the sentence says what to write instead.
OUTPUT_PATTERNS = (
    (re.compile(r"import: not found|Syntax error: \"\(\" unexpected|from: can't read /var/mail"), "no_shebang",
     "a Python script was run by sh (`import: not found`): it has no #! line; make its first line "
     "#!/usr/bin/env python3"),
    (re.compile(r"/usr/bin/env: .python.: No such file or directory"), "python2",
     "`#!/usr/bin/env python` asks for `python`, which this machine does not have: write "
     "#!/usr/bin/env python3 (%s)" % PYTHON3_FORM),
    (re.compile(r"NameError: name 'raw_input' is not defined"), "python2",
     "raw_input is Python 2; %s: write input(...)" % PYTHON3_FORM),
    (re.compile(r"SyntaxError: Missing parentheses in call to 'print'"), "python2",
     "`print x` is Python 2's print statement; %s: write print(x)" % PYTHON3_FORM),
    (re.compile(r"'float' object cannot be interpreted as an integer|indices must be integers or slices, not float"),
     "python2", "a / between integers gives a float in Python 3 (it gave an integer in Python 2), where an integer "
     "is needed: write // for integer division"),
)


def output_problems(text: str) -> List[str]:
    """The sentences (causes.Finding) for the mistakes `text` (a process's output) shows."""
    return [causes.finding(key, sentence) for pattern, key, sentence in OUTPUT_PATTERNS if pattern.search(text)]
