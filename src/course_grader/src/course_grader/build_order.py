"""A build that worked by luck: a C++ target that includes a header of its workspace's own
messages, with nothing making it wait for them to be generated.

catkin_make runs make in parallel, and without `add_dependencies(<target>
${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})` make may compile the target
before the header exists (`fatal error: my_chatter/TimestampString.h: No such file or
directory`): on one machine it builds, on another, or with one more core, it does not. The
verdict must not depend on that race, so after a build that worked this reads what make was
told (CMake's Makefile2: which target waits for which) and what the compiler read (each
object's `.o.d` dependency file), and finds the targets that include a generated header
without waiting, directly or through another target, for its generation.

The build folder is the student's: it is read through `student_files.read_tree` (no link
followed, bounded), and a file that says nothing parseable just finds nothing.
"""
from __future__ import annotations

import os
import re
from typing import Dict, Iterable, List, NamedTuple, Set

from course_grader.student_files import read_tree

_RULE = re.compile(r"^(?P<target>\S+)\.dir/all:(?P<deps>[^\n]*)$", re.MULTILINE)
_GENERATION = re.compile(r"(?:^|/)CMakeFiles/(?P<package>[\w-]+)_generate_messages_cpp$")
_DEPFILE_BYTES = 4 * 1024 * 1024
_MAX_DEPFILES = 2000


class Unordered(NamedTuple):
    package: str  # the target's folder in the workspace's src
    target: str  # the CMake target (the executable's name)
    header: str  # the generated header it includes, e.g. my_chatter/TimestampString.h

    def reason(self) -> str:
        return ("%s's %s includes %s, generated from %s's messages, but nothing makes its build wait for them: "
                "it built here only because make happened to generate them first (on a clean workspace, "
                "catkin_make -j2 can fail with `fatal error: %s: No such file or directory`)\n"
                "hint: add add_dependencies(%s ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS}) "
                "after add_executable(%s ...) in %s/CMakeLists.txt"
                % (self.package, self.target, self.header, self.header.split("/")[0], self.header,
                   self.target, self.target, self.package))


def waits_for(makefile2: str) -> Dict[str, Set[str]]:
    """Target folder (`pkg/CMakeFiles/node`) -> the targets it waits for, directly."""
    graph: Dict[str, Set[str]] = {}
    for m in _RULE.finditer(makefile2):
        deps = graph.setdefault(m.group("target"), set())
        deps.update(d[:-len(".dir/all")] for d in m.group("deps").split() if d.endswith(".dir/all"))
    return graph


def closure(graph: Dict[str, Set[str]], start: str) -> Set[str]:
    """Every target `start` waits for, directly or not."""
    seen: Set[str] = set()
    todo = list(graph.get(start, ()))
    while todo:
        target = todo.pop()
        if target not in seen:
            seen.add(target)
            todo.extend(graph.get(target, ()))
    return seen


def generated_by(graph: Dict[str, Set[str]]) -> Dict[str, str]:
    """Package whose C++ message headers this build generates -> its generation target."""
    found = {}
    for target in graph:
        m = _GENERATION.search(target)
        if m:
            found[m.group("package")] = target
    return found


def included_headers(depfile: str, devel_include: Iterable[str]) -> Set[str]:
    """The headers under a devel/include folder that a `.o.d` file lists, as `pkg/Header.h`."""
    found = set()
    for token in depfile.replace("\\\n", " ").split():
        for root in devel_include:
            if token.startswith(root + "/"):
                found.add(token[len(root) + 1:])
    return found


def unordered(ws: str) -> List[Unordered]:
    """The targets of the build in `ws` that include a header of the workspace's own messages
    without waiting for its generation (see the module docstring)."""
    build = os.path.join(ws, "build")
    makefiles = dict(read_tree(build, lambda p: p == os.path.join("CMakeFiles", "Makefile2"),
                               max_files=1, max_bytes=_DEPFILE_BYTES))
    graph = waits_for(makefiles.get(os.path.join("CMakeFiles", "Makefile2"), b"").decode("utf-8", "replace"))
    generation = generated_by(graph)
    if not generation:
        return []
    roots = sorted({os.path.join(ws, "devel", "include"), os.path.join(os.path.realpath(ws), "devel", "include")})
    problems: Dict[tuple, Unordered] = {}
    for path, data in read_tree(build, lambda p: p.endswith(".o.d"), max_files=_MAX_DEPFILES,
                                max_bytes=_DEPFILE_BYTES):
        target = path.split(".dir/", 1)[0]
        if target not in graph:
            continue
        waited = closure(graph, target)
        for header in sorted(included_headers(data.decode("utf-8", "replace"), roots)):
            package = header.split("/", 1)[0]
            if package in generation and generation[package] not in waited and generation[package] != target:
                folder = target.split("/CMakeFiles/")[0] if "/CMakeFiles/" in target else ""
                name = target.rsplit("/", 1)[-1]
                problems.setdefault((folder, name, package), Unordered(folder, name, header))
    return list(problems.values())
