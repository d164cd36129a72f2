"""The docs name only what exists: README.md, docs/**/*.md and src/*/README.md, checked on the tree.

Each failure names the document, the line and the missing thing. What is checked, and what is not:

- **Relative links** (`[text](target)`, `![alt](target)`, `[ref]: target`): the file or folder
  must exist, resolved from the document's folder. With `#anchor` on a Markdown file, a heading of
  that file must have that GitHub slug (lower case; punctuation but `-` and `_` dropped; each space
  a `-`; `-1`, `-2` for repeats); `#anchor` alone is a heading of the document itself. Not checked:
  URLs with a scheme (`https:`, `mailto:`), site paths (`/roslab/`), and targets that leave the
  repository (`../../shared/...`: not part of a checkout).
- **`make <target>`** in an inline code span or a line of a `sh`/`bash`/`shell`/`console` fenced
  block: each target after `make` (options and `VAR=value` skipped, up to the end of that command)
  must be a target of the Makefile. `catkin_make` and the like are not `make`.
- **Repository paths** in inline code spans and in those fenced blocks: a word that starts with a
  top-level folder of this checkout followed by `/` (`src/...`, `tools/x.py`, `deploy/...`) must
  exist (a trailing `:line` or `:line:col` is dropped). Not repository paths, so not checked:
  words with a placeholder or a pattern (`<pkg>`, `X`, `*`, `?`, `{`, `$`, `...`, `~`), the two
  catkin workspaces `catkin_ws/` and `solutions_ws/` (a student's workspace has the same name, and
  their contents are generated or links), git-ignored top-level folders (`output/`, `grades/`),
  any top-level folder this checkout lacks (the student image has no `solutions/`), and the
  arguments of a CMake or function call (`add_executable(node src/node.cpp)`: a student's package).
- **The course's packages' files and modules**, in the same places: `<pkg>/<file>` and
  `<pkg>.<module>`, where `<pkg>` is a package of `src/`. The file (a name with an extension:
  `course_grader/verdict.py`, `course_milestones/nodes/x_check.py`) must be in `src/<pkg>/` or in
  its Python package `src/<pkg>/src/<pkg>/`; the module (`course_grader.similarity`,
  `course_testkit.master.PrivateMaster`: its first part) must be a `.py` file or a folder there.
  Not checked: a message type or a `rosrun` name (`turtlesim/Pose`, `turtle_tf2/tf2_echo`: no
  extension), a file named after a package (`turtlesim.launch`: `.launch` is an extension), the
  reference solutions' and students' packages (`my_chatter/msg/...`: not the course's).
"""
from __future__ import annotations

import os
import re
import shlex
import unicodedata
from pathlib import Path
from typing import Iterable, Iterator, List, Optional, Set, Tuple
from urllib.parse import unquote

import pytest

ROOT = Path(__file__).resolve().parents[1]
WORKSPACES = {"catkin_ws", "solutions_ws"}
SHELL_FENCES = {"sh", "bash", "shell", "console", "zsh"}
FENCE = re.compile(r"^\s{0,3}(`{3,}|~{3,})\s*([\w+-]*)")
INLINE_CODE = re.compile(r"(?<!`)(`+)(?!`)(.+?)(?<!`)\1(?!`)")
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*(<[^>]*>|[^\s)]+)(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
HTML_ANCHOR = re.compile(r"<a\s+(?:name|id)=\"([^\"]+)\"", re.I)
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
PLACEHOLDER = re.compile(r"[<>*?{}$~\[\]]|\.\.\.|…|(^|/)[A-Z](/|$)")
FILE_EXTENSION = re.compile(r"\.[A-Za-z0-9]{1,8}$")
EXTENSIONS = {"py", "launch", "test", "xml", "yaml", "yml", "msg", "srv", "action", "txt", "csv", "json",
              "md", "png", "pdf", "svg", "cpp", "h", "hpp", "sh", "bash", "urdf", "sdf", "world", "rviz",
              "cfg", "xacro", "dae", "stl", "log", "html", "js", "css", "zip", "gz"}
CALL = re.compile(r"^[A-Za-z_][\w.:]*\(")
MAKE = re.compile(r"(?:^|(?<=[\s;&|(]))make(?=\s)")
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")
MAKE_OPTIONS_WITH_ARGUMENT = {"-C", "-f", "-I", "-o", "-W", "--directory", "--file", "--makefile"}
COMMAND_PREFIXES = {"sudo", "env", "time", "nohup", "exec", "command"}
SHELL_OPERATORS = {"&&", "||", ";", "|", "&", "(", ")", ";;", ">", ">>", "<", "2>", "2>&1"}


# ---------------------------------------------------------------- parsing: pure functions

def lines_outside_fences(text: str) -> Iterator[Tuple[int, str]]:
    """(line number, line) of every line that is not inside a fenced code block."""
    for number, line, fence in _lines_with_fences(text):
        if fence is None:
            yield number, line


def shell_fence_lines(text: str) -> Iterator[Tuple[int, str]]:
    """(line number, line) of every line inside a sh/bash/shell/console fenced block."""
    for number, line, fence in _lines_with_fences(text):
        if fence in SHELL_FENCES:
            yield number, line


def _lines_with_fences(text: str) -> Iterator[Tuple[int, str, Optional[str]]]:
    """Each line with the info string of the fence it is in (None outside; the fence lines
    themselves are left out)."""
    opened: Optional[str] = None
    info = None
    for number, line in enumerate(text.splitlines(), 1):
        match = FENCE.match(line)
        if opened is None and match:
            opened, info = match.group(1), match.group(2).lower()
            continue
        if opened is not None and match and match.group(1)[0] == opened[0] \
                and len(match.group(1)) >= len(opened) and not match.group(2):
            opened = info = None
            continue
        yield number, line, (None if opened is None else info)


def code_spans(line: str) -> List[str]:
    """The inline code spans of one line, their contents stripped."""
    return [match.group(2).strip() for match in INLINE_CODE.finditer(line)]


def without_code_spans(line: str) -> str:
    return INLINE_CODE.sub(lambda match: " " * len(match.group(0)), line)


def link_targets(line: str) -> List[str]:
    """The targets of the Markdown links and images of one line (code spans are not links)."""
    line = without_code_spans(line)
    targets = [match.group(1) for match in LINK.finditer(line)]
    reference = REFERENCE.match(line)
    if reference:
        targets.append(reference.group(1))
    return [target[1:-1] if target.startswith("<") else target for target in targets]


def github_slug(heading: str) -> str:
    """The anchor GitHub gives a heading: its text (markup dropped) in lower case, every character
    but letters, digits, `-`, `_` and spaces dropped, each space a hyphen."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link: its text
    text = re.sub(r"<[^>]+>", "", text)  # inline HTML
    text = text.replace("`", "").replace("*", "")
    text = text.strip().lower()
    kept = "".join(c for c in text
                   if c in " -_" or unicodedata.category(c)[0] in "LN" or unicodedata.category(c) == "Mn")
    return kept.replace(" ", "-")


def heading_anchors(text: str) -> Set[str]:
    """Every anchor a document offers: its headings' slugs (repeats get -1, -2, ...) and any
    `<a name=...>` / `<a id=...>`."""
    anchors: Set[str] = set()
    seen: dict = {}
    for _number, line in lines_outside_fences(text):
        match = HEADING.match(line)
        if match:
            slug = github_slug(match.group(2))
            count = seen.get(slug, 0)
            seen[slug] = count + 1
            anchors.add(slug if count == 0 else "%s-%d" % (slug, count))
        anchors.update(HTML_ANCHOR.findall(line))
    return anchors


def make_targets_named(command: str) -> List[str]:
    """The Makefile targets a command line runs with `make`: `make` as a command (at the start,
    after `&&`, `;`, `|`, `sudo`, `VAR=value`) or as the command a `docker run`/`podman run` gives
    its container. `apt-get install make` and `catkin_make` are not make; placeholders such as
    `<target>` are left out."""
    words = _shell_words(command)
    targets: List[str] = []
    at_start, index = True, 0
    while index < len(words):
        word = words[index]
        index += 1
        if word in SHELL_OPERATORS:
            at_start = True
            continue
        if not at_start:
            continue
        if word in COMMAND_PREFIXES or ASSIGNMENT.match(word) or word.startswith("-"):
            continue
        at_start = False
        if word in ("docker", "podman"):  # the container's command: the first `make` word of it
            rest = words[index:]
            end = next((i for i, w in enumerate(rest) if w in SHELL_OPERATORS), len(rest))
            if "make" not in rest[:end]:
                continue
            index += rest.index("make") + 1
            word = "make"
        if word == "make":
            index = _make_arguments(words, index, targets)
    return targets


def _shell_words(command: str) -> List[str]:
    command = re.sub(r"(^|\s)#.*$", "", command)  # a shell comment
    try:
        lexer = shlex.shlex(command, posix=True, punctuation_chars=True)
        lexer.whitespace_split = True
        return list(lexer)
    except ValueError:  # an unbalanced quote (a code span cut short): split by hand
        return re.findall(r"&&|\|\||[;|&()]|[^\s;|&()]+", command)


def _make_arguments(words: List[str], index: int, targets: List[str]) -> int:
    """Appends the targets among make's arguments from words[index]; returns where they end."""
    while index < len(words):
        word = words[index]
        if word in SHELL_OPERATORS:
            break
        index += 1
        if word in MAKE_OPTIONS_WITH_ARGUMENT:
            index += 1
        elif word.startswith("-") or ASSIGNMENT.match(word):
            continue
        elif re.match(r"^[\w.-]+$", word) and not PLACEHOLDER.search(word):
            targets.append(word)
        elif re.search(r"['’]s$", word):  # prose, "make hub's start": no more arguments
            break
    return index


def repo_path_words(text: str, top_dirs: Iterable[str]) -> List[str]:
    """The words of a code span (or a shell line) that name a path in the repository: those that
    start with one of top_dirs and a `/`; a trailing `:line[:col]`, a pytest node id's `::test`
    and punctuation dropped. Placeholders, patterns and the arguments of a call
    (`add_executable(x src/x.cpp)`) are not repository paths."""
    if CALL.match(text):
        return []
    tops = set(top_dirs)
    paths = []
    for word in re.split(r"[\s\"'=,;|&()]+", text):
        if PLACEHOLDER.search(word):
            continue
        word = re.sub(r"(:\d+){1,2}$", "", word.split("::", 1)[0].strip(".:"))
        if "/" not in word:
            continue
        if word.split("/", 1)[0] in tops:
            paths.append(word)
    return paths


def package_references(text: str, packages: Iterable[str], python_packages: Iterable[str]) -> List[Tuple[str, List[str]]]:
    """The course's files and modules a code span names: (the word, the repository paths any one of
    which must exist). `<pkg>/<file with an extension>` is in `src/<pkg>/` or `src/<pkg>/src/<pkg>/`;
    `<pkg>.<module>` (pkg one of python_packages) is a module or a folder of `src/<pkg>/src/<pkg>/`."""
    if CALL.match(text):
        return []
    packages, python_packages = set(packages), set(python_packages)
    found: List[Tuple[str, List[str]]] = []
    for word in re.split(r"[\s\"'=,;|&()]+", text):
        if PLACEHOLDER.search(word):
            continue
        word = re.sub(r"(:\d+){1,2}$", "", word.split("::", 1)[0].strip(".:"))
        slash = re.match(r"^([A-Za-z][\w-]*)/(.+)$", word)
        if slash and slash.group(1) in packages and FILE_EXTENSION.search(slash.group(2).rstrip("/")):
            pkg, rest = slash.groups()
            found.append((word, ["src/%s/%s" % (pkg, rest), "src/%s/src/%s/%s" % (pkg, pkg, rest)]))
            continue
        dotted = re.match(r"^([A-Za-z]\w*)\.([A-Za-z_]\w*)(?:\.\w+)*$", word)
        if dotted and dotted.group(1) in python_packages and dotted.group(2) not in EXTENSIONS:
            pkg, module = dotted.groups()
            found.append((word, ["src/%s/src/%s/%s.py" % (pkg, pkg, module), "src/%s/src/%s/%s" % (pkg, pkg, module)]))
    return found


def makefile_targets(makefile: str) -> Set[str]:
    """The targets a Makefile defines (rules' left-hand sides; not variables, not recipes)."""
    targets: Set[str] = set()
    for line in makefile.splitlines():
        if line.startswith("\t") or line.lstrip().startswith("#"):
            continue
        match = re.match(r"^([^:=#\s][^:=#]*?)\s*::?(?!=)", line)
        if match and not re.match(r"^\s*(ifeq|ifneq|ifdef|ifndef|else|endif|define|export)\b", line):
            targets.update(name for name in match.group(1).split() if "$" not in name)
    return targets


def ignored_top_dirs(gitignore: str) -> Set[str]:
    """Top-level folders a .gitignore leaves out (`/name/` or `/name`)."""
    return {line.strip().strip("/") for line in gitignore.splitlines()
            if re.match(r"^/[^/*?\[\]#\s]+/?\s*$", line.strip())}


# ---------------------------------------------------------------- the check of one document

def check_document(path: Path, root: Path, targets: Set[str], top_dirs: Set[str],
                   packages: Tuple[Set[str], Set[str]] = (set(), set())) -> List[str]:
    """Every missing thing one document names, as `doc:line: what`."""
    text = path.read_text(encoding="utf-8")
    name = path.relative_to(root).as_posix()
    problems: List[str] = []
    own_anchors = heading_anchors(text)
    for number, line in lines_outside_fences(text):
        where = "%s:%d" % (name, number)
        for target in link_targets(line):
            problem = check_link(target, path, root, own_anchors)
            if problem:
                problems.append("%s: link (%s): %s" % (where, target, problem))
        for span in code_spans(line):
            problems.extend(_check_code(span, where, root, targets, top_dirs, packages))
    for number, line in shell_fence_lines(text):
        problems.extend(_check_code(line, "%s:%d" % (name, number), root, targets, top_dirs, packages))
    return sorted(problems, key=lambda problem: int(problem.split(":", 2)[1]))  # by line


def _check_code(code: str, where: str, root: Path, targets: Set[str], top_dirs: Set[str],
                packages: Tuple[Set[str], Set[str]]) -> List[str]:
    problems = ["%s: make %s: no such target in the Makefile" % (where, target)
                for target in make_targets_named(code) if target not in targets]
    problems += ["%s: %s: no such file or folder in the repository" % (where, word)
                 for word in repo_path_words(code, top_dirs) if not (root / word).exists()]
    problems += ["%s: %s: not in the repository (looked for %s)" % (where, word, ", ".join(candidates))
                 for word, candidates in package_references(code, *packages)
                 if not any((root / candidate).exists() for candidate in candidates)]
    return problems


def check_link(target: str, document: Path, root: Path, own_anchors: Set[str]) -> Optional[str]:
    """Why a link's target is missing, or None when it is there (or not ours to check)."""
    if SCHEME.match(target) or target.startswith("/"):
        return None
    path_part, _, anchor = target.partition("#")
    if not path_part:
        return None if anchor in own_anchors else "no heading #%s in this document" % anchor
    resolved = Path(os.path.normpath(document.parent / unquote(path_part)))
    try:
        resolved.relative_to(root)
    except ValueError:
        return None  # outside the repository (../shared beside a clone): not checked
    if not resolved.exists():
        return "no such file"
    if anchor and resolved.suffix == ".md" and resolved.is_file():
        if anchor not in heading_anchors(resolved.read_text(encoding="utf-8")):
            return "%s has no heading #%s" % (resolved.relative_to(root).as_posix(), anchor)
    return None


def documents(root: Path) -> List[Path]:
    found = [root / "README.md"] + sorted((root / "docs").rglob("*.md")) + sorted(root.glob("src/*/README.md"))
    return [path for path in found if path.is_file()]


def course_packages(root: Path) -> Tuple[Set[str], Set[str]]:
    """The packages of src/, and those of them with a Python package of their own name."""
    packages = {path.parent.name for path in root.glob("src/*/package.xml")}
    return packages, {name for name in packages if (root / "src" / name / "src" / name).is_dir()}


def top_level_dirs(root: Path) -> Set[str]:
    gitignore = root / ".gitignore"
    ignored = ignored_top_dirs(gitignore.read_text()) if gitignore.is_file() else set()
    return {entry.name for entry in root.iterdir()
            if entry.is_dir() and not entry.name.startswith(".")} - ignored - WORKSPACES


# ---------------------------------------------------------------- the check, on the tree

def test_docs_name_only_what_exists():
    targets = makefile_targets((ROOT / "Makefile").read_text())
    top_dirs = top_level_dirs(ROOT)
    assert {"src", "docs", "tools"} <= top_dirs and {"demo", "test", "grade"} <= targets
    packages = course_packages(ROOT)
    assert {"course_grader", "turtlesim"} <= packages[0]
    problems = [problem for path in documents(ROOT)
                for problem in check_document(path, ROOT, targets, top_dirs, packages)]
    assert not problems, "the docs name what is not there:\n" + "\n".join(problems)


# ---------------------------------------------------------------- the parsing, on small strings

def test_fences_are_told_apart():
    text = "a `x`\n```sh\nmake demo\n```\n```\nok make hub's start\n```\nb\n"
    assert [n for n, _ in lines_outside_fences(text)] == [1, 8]
    assert list(shell_fence_lines(text)) == [(3, "make demo")]


def test_a_longer_fence_holds_a_shorter_one():
    text = "````md\n```sh\nmake nothing\n```\n````\nafter\n"
    assert list(lines_outside_fences(text)) == [(6, "after")]
    assert list(shell_fence_lines(text)) == []


def test_code_spans():
    assert code_spans("run `make demo` and ``a `b` c``, not `") == ["make demo", "a `b` c"]


def test_links_but_not_in_code():
    line = "see [the guide](grading.md#outputs), ![pic](a.png \"t\") and `[x](nope.md)` [r](<b c.md>)"
    assert link_targets(line) == ["grading.md#outputs", "a.png", "b c.md"]
    assert link_targets("[docs/grading.md](docs/grading.md) [`x`](y.md)") == ["docs/grading.md", "y.md"]
    assert link_targets("[ref]: ../tools/x.py") == ["../tools/x.py"]


@pytest.mark.parametrize("heading, slug", [
    ("What a student's code can and cannot do (`course_sandbox`)",
     "what-a-students-code-can-and-cannot-do-course_sandbox"),
    ("Where a grading's time goes (`bench/milestone_profile.py`)",
     "where-a-gradings-time-goes-benchmilestone_profilepy"),
    ("The course, the reference solutions, and what a student's package sees",
     "the-course-the-reference-solutions-and-what-a-students-package-sees"),
    ("Simulator window (gui:=true)", "simulator-window-guitrue"),
    ("ROS_DOMAIN_ID -> one master per group", "ros_domain_id---one-master-per-group"),
    ("A **bold** [link](x.md) here", "a-bold-link-here"),
])
def test_github_slug(heading, slug):
    assert github_slug(heading) == slug


def test_heading_anchors_count_repeats_and_skip_code():
    text = "# Figures\n## Figures\n```sh\n# not a heading\n```\n<a name=\"here\"></a>\n"
    assert heading_anchors(text) == {"figures", "figures-1", "here"}


@pytest.mark.parametrize("command, targets", [
    ("make demo", ["demo"]),
    ("sudo make hub-password RESET=alice", ["hub-password"]),
    ("JUPYTER_PORT=8889 make jupyter", ["jupyter"]),
    ("make flake-hunt K=20 UNTIL_FAIL=1 ARGS=\"tests/test_rostests.py -k camera\"", ["flake-hunt"]),
    ("make demo   # then make nothing", ["demo"]),
    ("make build && make demo; make -C x test", ["build", "demo", "test"]),
    ("docker run --rm -it ros-course make jupyter", ["jupyter"]),
    ("make -j2", []),
    ("make <target>", []),
    ("catkin_make install && cmake ..", []),
    ("make hub's own start", []),
    ("apt-get install -y make sudo ca-certificates   # then: make demo", []),
    ("sudo -E make hub; podman run -d -p 1:2 IMAGE make jupyter", ["hub", "jupyter"]),
    ("make docker-check DOCKER_CHECK_ARGS=\"--rebuild", ["docker-check"]),
])
def test_make_targets_named(command, targets):
    assert make_targets_named(command) == targets


@pytest.mark.parametrize("code, paths", [
    ("src/course_grader/src/course_grader/cli.py", ["src/course_grader/src/course_grader/cli.py"]),
    ("python3 tools/flake_hunt.py 2 src/course_relay", ["tools/flake_hunt.py", "src/course_relay"]),
    ("src/turtlesim/node.py:12:3,", ["src/turtlesim/node.py"]),
    ("tests/e2e/test_image.py::test_the_course_images", ["tests/e2e/test_image.py"]),
    ("src/<pkg>/test/unit/", []),
    ("src/X/", []),
    ("courses/robotics_labs/samples/attack_*", []),
    ("src/course_grader/...", []),
    ("~/catkin_ws/src/chatter", []),
    ("catkin_ws/devel/setup.bash", []),
    ("my_pkg/src/node.cpp", []),
    ("add_executable(pose_subscriber src/pose_subscriber.cpp)", []),
    ("deploy/jupyterhub/", ["deploy/jupyterhub/"]),
    ("src", []),
])
def test_repo_path_words(code, paths):
    assert repo_path_words(code, {"src", "tools", "tests", "deploy"}) == paths


@pytest.mark.parametrize("code, found", [
    ("course_grader/verdict.py", [("course_grader/verdict.py", ["src/course_grader/verdict.py",
                                                               "src/course_grader/src/course_grader/verdict.py"])]),
    ("python3 -m course_grader.similarity", [("course_grader.similarity", [
        "src/course_grader/src/course_grader/similarity.py", "src/course_grader/src/course_grader/similarity"])]),
    ("course_testkit.master.PrivateMaster", [("course_testkit.master.PrivateMaster", [
        "src/course_testkit/src/course_testkit/master.py", "src/course_testkit/src/course_testkit/master"])]),
    ("rossrv info turtlesim/SetPen", []),
    ("rosrun turtle_tf2 tf2_echo; turtle_tf2/tf2_echo", []),
    ("roslaunch mybot_teleop turtlesim.launch", []),
    ("my_chatter/msg/TimestampString.msg", []),
    ("turtlesim/Pose course_graph/<x>.py", []),
    ("course_env.", []),
])
def test_package_references(code, found):
    assert package_references(code, {"course_grader", "course_testkit", "turtlesim", "turtle_tf2", "course_graph",
                                     "course_env"},
                              {"course_grader", "course_testkit", "turtlesim", "course_env"}) == found


def test_makefile_targets():
    makefile = (".PHONY: a b\nVAR := x\nOTHER ?= y\na: b\n\t@echo c: d\nb c:\n"
                "ifneq ($(X),)\nendif\n$(OUT): a\n# e: f\n")
    assert makefile_targets(makefile) == {".PHONY", "a", "b", "c"}


def test_ignored_top_dirs():
    assert ignored_top_dirs("/output/\n/grades/\n__pycache__/\n/catkin_ws/build/\n*.pyc\n/.hub/\n") == \
        {"output", "grades", ".hub"}


def test_check_document_names_line_and_missing_thing(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "tools").mkdir()
    (tmp_path / "tools" / "x.py").write_text("")
    (tmp_path / "docs" / "b.md").write_text("# Real heading\n")
    doc = tmp_path / "docs" / "a.md"
    doc.write_text("# A\n"
                   "[ok](b.md#real-heading) [gone](c.md) [bad](b.md#nothing) [self](#a) [out](../../x.md)\n"
                   "`make demo`, `make nope`, `tools/x.py`, `tools/y.py`, [web](https://example.org)\n"
                   "```sh\nmake nope2\npython3 tools/z.py\n```\n"
                   "`pkg.mod`, `pkg.gone.Thing`, `pkg/nodes/check.py`\n")
    (tmp_path / "src" / "pkg" / "src" / "pkg").mkdir(parents=True)
    (tmp_path / "src" / "pkg" / "src" / "pkg" / "mod.py").write_text("")
    problems = check_document(doc, tmp_path, {"demo"}, {"docs", "tools"}, ({"pkg"}, {"pkg"}))
    assert problems == [
        "docs/a.md:2: link (c.md): no such file",
        "docs/a.md:2: link (b.md#nothing): docs/b.md has no heading #nothing",
        "docs/a.md:3: make nope: no such target in the Makefile",
        "docs/a.md:3: tools/y.py: no such file or folder in the repository",
        "docs/a.md:5: make nope2: no such target in the Makefile",
        "docs/a.md:6: tools/z.py: no such file or folder in the repository",
        "docs/a.md:8: pkg.gone.Thing: not in the repository (looked for src/pkg/src/pkg/gone.py, src/pkg/src/pkg/gone)",
        "docs/a.md:8: pkg/nodes/check.py: not in the repository (looked for src/pkg/nodes/check.py, "
        "src/pkg/src/pkg/nodes/check.py)",
    ]
