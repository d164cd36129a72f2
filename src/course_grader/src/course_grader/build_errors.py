"""What a failed catkin_make says is wrong, in the order a student fixes it.

First the compiler's and the linker's own error lines (each undefined reference named once),
with paths as the student knows them (`my_pkg/src/node.cpp:14:14`, not the grader's workspace
path), then a one-line hint for the mistakes students make most (a target not linked with
`${catkin_LIBRARIES}`, a package find_package cannot find, a header of the package's own
messages compiled before it is generated) and for code written for ROS Noetic that Debian 12
still does not compile (docs/noetic_cxx.md: a bind placeholder `_1` ambiguous or undeclared,
ROS_INFO without ros/console.h, a C++14 `throw(...)` under GCC 12's C++17), then CMake's,
catkin's and Python's own errors.
Warnings are never shown as the reason: they never fail a build.
"""
from __future__ import annotations

import os
import re
from typing import Callable, Dict, Iterable, List, NamedTuple, Optional, Sequence, Set

from course_grader import student_files
from course_format import causes

SUMMARY_LINES = 25
MAX_UNDEFINED = 6
# Where a failed build says why: CMake errors, catkin's and Python's complaints, make's summary.
_ERROR_START = re.compile(r"CMake Error|\berror:|fatal error|^Error|Traceback \(most recent|Multiple packages|"
                          r"^make(\[\d+\])?: \*\*\*")
_COMPILER_ERROR = re.compile(r"^(?P<file>[^\s:][^:]*):(?P<line>\d+):(?:(?P<col>\d+):)? (?:fatal )?error: (?P<what>.*)")
_CONTEXT = re.compile(r"^[^\s:][^:]*: (?:In (?:member |static member )?function|In constructor|In destructor|"
                      r"At global scope|In instantiation of)")
_MISSING_HEADER = re.compile(r"^(?P<header>(?P<package>[\w.-]+)/[\w./-]+): No such file or directory")
_UNDEFINED = re.compile(r"^(?:(?P<object>[^\s:]+):\S*: )?undefined reference to [`'](?P<symbol>.*)'$")
_IN_FUNCTION = re.compile(r"^(?:/usr/bin/ld: )?(?P<object>\S+\.o): in function")
_OBJECT = re.compile(r"(?:^|/)CMakeFiles/(?P<target>[^/\s]+)\.dir/(?P<source>\S+)\.o$")
_MAKE_FAILED = re.compile(r"^make\[\d+\]: \*\*\* \[(?P<package>[^\s:\]]*?)/?CMakeFiles/(?P<target>[^/\s]+)\.dir/"
                          r"build\.make:\d+: (?P<output>[^\]]+)\] Error")
_LINKER_DONE = re.compile(r"^collect2: error: ld returned")
_NO_PACKAGE = re.compile(r'Could not find a package configuration file provided by\s+"(?P<package>[^"]+)"')
# catkin_package() CATKIN_DEPENDS on a package found but not in package.xml (the message wraps).
_NOT_BUILD_DEPEND = re.compile(r"catkin package '(?P<dep>[^']+)' has been find_package\(\)-ed but\s+is not listed as a "
                               r"build dependency in the package\.xml")
_CATKIN_PACKAGE_CALL = re.compile(r"^\s*(?P<folder>[^\s/][^\s]*)/CMakeLists\.txt:\d+ \(catkin_package\)", re.MULTILINE)
# catkin_pkg refusing a tag of another format (format 1 is a <package> without format="...").
_OTHER_FORMAT_TAGS = re.compile(r'The manifest of package "(?P<package>[^"]+)" \(with format version (?P<format>\d+)\) '
                                r"must not contain the following tags: (?P<tags>[\w, ]+)")
_MANIFEST_ERRORS = re.compile(r"Error\(s\) in package '(?P<folder>[^\s/'][^\s']*)/package\.xml'")
_FORMAT = re.compile(r"<package\b[^>]*?\bformat\s*=\s*[\"'](?P<format>\d+)[\"']")
_MESSAGE_PACKAGE = re.compile(r"^-- (?P<package>[\w-]+): \d+ messages, \d+ services", re.MULTILINE)
# g++ quotes names with ‘’ in a UTF-8 locale and with '' in the C locale.
_Q = "[‘']"
_EQ = "[’']"
# Compiler errors that code written for ROS Noetic (Ubuntu 20.04: GCC 9, C++14, ROS headers that
# included <boost/bind.hpp> and pluginlib headers that included ros/console.h) meets here even
# with course_env's compatibility headers, and what to write instead.
_NOETIC_HINTS = (
    (re.compile("reference to %s(?P<name>_[1-9])%s is ambiguous" % (_Q, _EQ)),
     "hint: %(name)s is both boost::placeholders::%(name)s, global wherever a ROS header is included (as on "
     "ROS Noetic), and std::placeholders::%(name)s, which `using namespace std::placeholders;` adds: write "
     "std::placeholders::%(name)s in std::bind (boost::placeholders::%(name)s in boost::bind), or drop the "
     "using-directive"),
    (re.compile("%s(?P<name>_[1-9])%s was not declared in this scope" % (_Q, _EQ)),
     "hint: %(name)s is a placeholder of boost::bind or std::bind: write boost::placeholders::%(name)s "
     "(std::placeholders::%(name)s with std::bind); it is global, as on ROS Noetic, only in a file that "
     "includes a ROS header (or boost/bind.hpp) built in the course's environment "
     "(`source <course>/catkin_ws/devel/setup.bash`)"),
    (re.compile("%s(?P<name>ROS_[A-Z_]+)%s was not declared in this scope" % (_Q, _EQ)),
     "hint: %(name)s comes from ros/console.h: add #include <ros/ros.h> to this file (Debian 12's "
     "pluginlib .hpp headers, unlike Noetic's, do not include it for you)"),
    (re.compile(r"ISO C\+\+17 does not allow dynamic exception specifications"),
     "hint: GCC 12 compiles C++17, where `throw(...)` after a function's parameters is an error (ROS "
     "Noetic's GCC 9 compiled C++14): write noexcept instead, or drop it"),
)
# Noetic's pluginlib had these .h names beside the .hpp headers; Debian 12's has only the .hpp
# (course_env adds the .h names back, in the course's environment only).
_PLUGINLIB_H = {"pluginlib/class_list_macros.h": "pluginlib/class_list_macros.hpp",
                "pluginlib/class_loader.h": "pluginlib/class_loader.hpp",
                "pluginlib/class_desc.h": "pluginlib/class_desc.hpp",
                "pluginlib/class_loader_base.h": "pluginlib/class_loader_base.hpp",
                "pluginlib/pluginlib_exceptions.h": "pluginlib/exceptions.hpp"}
_LIBSTDCXX_STRING = "std::__cxx11::basic_string<char, std::char_traits<char>, std::allocator<char> >"
# What ROS's macros and templates call behind the student's back (ROS_INFO, publish()): named
# after the functions the student's own code calls (ros::init, ros::NodeHandle::subscribe).
_PLUMBING = ("ros::console::", "ros::serialization::", "ros::SerializedMessage", "boost::")
_ROS_NAMESPACES = ("ros::", "tf2_ros::", "tf2::", "XmlRpc::", "actionlib::", "image_transport::", "message_filters::")


class Target(NamedTuple):
    package: str  # the package's folder in the workspace's src ("" when unknown)
    name: str  # the CMake target (the executable's name)

    def __str__(self) -> str:
        return "%s's %s" % (self.package, self.name) if self.package else self.name


def summarise(log: str, ws: str, lines: int = SUMMARY_LINES) -> str:
    """The reason a catkin_make log in workspace `ws` failed (see the module docstring); a
    package.xml the log blames is read from `ws` (as the student's: no link followed)."""
    text = relative_paths(log, ws)

    def package_xml(folder: str) -> Optional[str]:
        data = student_files.read_file(os.path.join(ws, "src"), folder + "/package.xml", 64 * 1024)
        return data.decode("utf-8", "replace") if data is not None else None
    all_lines = [_strip_colour(line.rstrip()) for line in text.splitlines()]
    targets = _failed_targets(all_lines)
    compiled = _compiler_errors(all_lines)
    undefined = _undefined(all_lines, targets)
    linked = _linker_errors(all_lines, undefined)
    hints = _hints(all_lines, compiled, undefined, targets, message_packages(text)) + _package_xml_hints(text, package_xml)
    first = compiled + linked
    rest = [] if first else _error_blocks(all_lines)
    if not first and not rest:
        rest = [line for line in all_lines if line.strip()][-lines:]
    return causes.finding(causes.of(hints[0], causes.BUILD_FAILED) if hints else causes.BUILD_FAILED,
                          "\n".join((first + rest)[:lines] + hints))


def relative_paths(text: str, ws: str) -> str:
    """`text` with the workspace's paths as the student knows them: `<ws>/src/pkg/x.cpp` is
    `pkg/x.cpp`, `<ws>/devel/lib/...` is `devel/lib/...`."""
    for root in sorted({ws.rstrip("/"), _real(ws)}, key=len, reverse=True):
        if root:
            text = text.replace(root + "/src/", "").replace(root + "/", "")
    return text


def message_packages(log: str) -> Set[str]:
    """The workspace's packages that generate messages or services (genmsg says so while CMake runs)."""
    return {m.group("package") for m in _MESSAGE_PACKAGE.finditer(log)}


def _real(path: str) -> str:
    return os.path.realpath(path).rstrip("/")


def _strip_colour(line: str) -> str:
    return re.sub(r"\x1b\[[0-9;]*m", "", line)


def _failed_targets(lines: Sequence[str]) -> Dict[str, Target]:
    """make's failed rules: the object or executable it was making -> the target it belongs to."""
    found: Dict[str, Target] = {}
    for line in lines:
        m = _MAKE_FAILED.match(line)
        if m:
            found[m.group("output")] = Target(m.group("package"), m.group("target"))
    return found


def _compiler_errors(lines: Sequence[str]) -> List[str]:
    """Each compiler error with the source line and caret g++ prints under it."""
    kept: List[str] = []
    for i, line in enumerate(lines):
        if not _COMPILER_ERROR.match(line):
            continue
        if i and _CONTEXT.search(lines[i - 1]) and lines[i - 1] not in kept[-4:]:
            kept.append(lines[i - 1])  # "x.cpp: In function 'int main(int, char**)':"
        kept.append(line)
        for follow in lines[i + 1:i + 3]:
            if re.match(r"^\s+\d*\s*\|", follow):
                kept.append(follow)
    return kept


class Undefined(NamedTuple):
    symbol: str
    source: str  # the student's source file that uses it ("" when the linker did not say)
    target: Optional[Target]


def _linker_errors(lines: Sequence[str], found: Sequence["Undefined"]) -> List[str]:
    """Each undefined reference once (by symbol), then the linker's last word."""
    undefined = sorted(found, key=lambda u: u.symbol.startswith(_PLUMBING))
    if not undefined:
        return [line for line in lines if _LINKER_DONE.match(line)][:1]
    kept = []
    for u in undefined[:MAX_UNDEFINED]:
        where = u.source or (u.target.name if u.target else "")
        kept.append("%sundefined reference to `%s'" % (where + ": " if where else "", u.symbol))
    if len(undefined) > MAX_UNDEFINED:
        kept.append("... and %d more undefined references" % (len(undefined) - MAX_UNDEFINED))
    kept += [line for line in lines if _LINKER_DONE.match(line)][:1]
    return kept


def _undefined(lines: Sequence[str], targets: Dict[str, Target]) -> List[Undefined]:
    seen: Set[str] = set()
    found: List[Undefined] = []
    obj = ""
    for line in lines:
        m = _IN_FUNCTION.match(line)
        if m:
            obj = m.group("object")
            continue
        m = _UNDEFINED.match(re.sub(r"^/usr/bin/ld: ", "", line))
        if not m:
            continue
        symbol = m.group("symbol").replace(_LIBSTDCXX_STRING, "std::string").replace("std::string >", "std::string>")
        if symbol in seen:
            continue
        seen.add(symbol)
        o = _OBJECT.search(obj)
        target = _target_of(o.group("target"), targets) if o else None
        source = "/".join(p for p in (target.package if target else "", o.group("source") if o else "") if p)
        found.append(Undefined(symbol, source, target))
    return found


def _target_of(name: str, targets: Dict[str, Target]) -> Target:
    for target in targets.values():
        if target.name == name:
            return target
    return Target("", name)


def _error_blocks(lines: Sequence[str]) -> List[str]:
    """Each other error block: the error line and the indented, listed or blank lines after it
    (CMake's reason and call stack, catkin_pkg's `- ` list of a package.xml's errors, a Python
    traceback's last line); make's own summary lines left out."""
    kept: List[str] = []
    i = 0
    while i < len(lines):
        if not _ERROR_START.search(lines[i]) or lines[i].startswith("make"):
            i += 1
            continue
        block = [lines[i]]
        i += 1
        while i < len(lines) and (not lines[i] or lines[i][0].isspace() or lines[i].startswith(("Call Stack", "- "))):
            block.append(lines[i])
            i += 1
        if block[0].startswith("Traceback") and i < len(lines):
            block.append(lines[i])  # the exception itself
            i += 1
        kept += [line for line in block if line.strip()]
    if not kept:
        kept = [line for line in lines if line.startswith("make") and "***" in line][:3]
    return kept


def _hints(lines: Sequence[str], compiled: Sequence[str], undefined: Sequence["Undefined"],
           targets: Dict[str, Target], own_messages: Iterable[str]) -> List[causes.Finding]:
    hints: List[causes.Finding] = []
    own = set(own_messages)
    noetic_hinted: Set[int] = set()  # one hint per kind (_1 and _2 undeclared: one hint)
    for line in compiled:
        m = _COMPILER_ERROR.match(line)
        missing = _MISSING_HEADER.match(m.group("what")) if m else None
        if missing:
            hints.append(_missing_header_hint(missing.group("header"), missing.group("package"),
                                              _compiled_by(m.group("file"), targets), own))
        for kind, (pattern, hint) in enumerate(_NOETIC_HINTS if m else ()):
            noetic = pattern.search(m.group("what"))
            if noetic and kind not in noetic_hinted:
                noetic_hinted.add(kind)
                hints.append(causes.finding("noetic_cxx", hint % noetic.groupdict()))
    ros = [u for u in undefined if u.symbol.startswith(_ROS_NAMESPACES)]
    if ros:
        target = ros[0].target or Target("", "<target>")
        cmake = "%s/CMakeLists.txt" % target.package if target.package else "CMakeLists.txt"
        hints.append(causes.finding(
            "not_linked", "hint: %s is not linked with the ROS libraries: in %s, name roscpp (and every ROS package "
                     "the code uses, e.g. tf2_ros) in find_package(catkin REQUIRED COMPONENTS ...), and add "
                     "target_link_libraries(%s ${catkin_LIBRARIES}) after add_executable(%s ...)"
                     % (target.name, cmake, target.name, target.name)))
    elif undefined:
        target = undefined[0].target or Target("", "<target>")
        hints.append(causes.finding(
            "not_compiled_in", "hint: a function used by %s is declared but never compiled into it: add the .cpp file "
                     "that defines it to add_executable(%s ...), or the library to target_link_libraries"
                     % (target.name, target.name)))
    for line in lines:
        m = _NO_PACKAGE.search(line)
        if m:
            hints.append(causes.finding(
                "unknown_package", "hint: %s is neither a package of this machine nor of the course workspace: check "
                         "its spelling in find_package(...) and in package.xml" % m.group("package")))
            break
    return [h for i, h in enumerate(hints) if h not in hints[:i]]  # each once, its cause kept


def package_format(text: Optional[str]) -> Optional[int]:
    """The format of a package.xml's text (1 when its <package> tag names none), None when unknown."""
    if text is None or "<package" not in text:
        return None
    m = _FORMAT.search(text)
    return int(m.group("format")) if m else 1


def _package_xml_hints(text: str, package_xml: Callable[[str], Optional[str]]) -> List[causes.Finding]:
    """What to write in package.xml when catkin refuses it: a dependency the build uses and the file
    does not list (in the tags of the file's own format), or a tag its format does not have."""
    hints: List[causes.Finding] = []
    missing = _NOT_BUILD_DEPEND.search(text)
    if missing:
        dep = missing.group("dep")
        call = _CATKIN_PACKAGE_CALL.search(text, missing.end())
        folder = call.group("folder") if call else ""
        where = "%s/package.xml" % folder if folder else "package.xml"
        manifest = package_xml(folder) if folder else None
        form = package_format(manifest)
        if form == 1:
            has_run = re.search(r"<run_depend>\s*%s\s*</run_depend>" % re.escape(dep), manifest or "") is not None
            add = ("<build_depend>%s</build_depend> next to its <run_depend>%s</run_depend>" % (dep, dep) if has_run
                   else "<build_depend>%s</build_depend> and <run_depend>%s</run_depend>" % (dep, dep))
            hint = ("hint: %s is format 1 (its <package> tag says no format=\"2\"), where each dependency is named "
                    "once per use: add %s (<depend> exists only from format 2)" % (where, add))
        elif form is not None:
            hint = ("hint: catkin_package() names %s, which find_package(catkin REQUIRED COMPONENTS ...) found, and "
                    "%s (format %d) does not list it: add <depend>%s</depend>" % (dep, where, form, dep))
        else:
            hint = ("hint: add %s to %s: <depend>%s</depend> in a <package format=\"2\">, or <build_depend>%s"
                    "</build_depend> and <run_depend>%s</run_depend> in a format 1 <package>" % (dep, where, dep, dep, dep))
        hints.append(causes.finding("package_xml", hint))
    other = _OTHER_FORMAT_TAGS.search(text)
    if other:
        form, tags = int(other.group("format")), [t.strip() for t in other.group("tags").split(",") if t.strip()]
        named = _MANIFEST_ERRORS.search(text)
        where = "%s/package.xml" % named.group("folder") if named else "the package.xml of %s" % other.group("package")
        if form == 1:
            hint = ("hint: %s is read as format 1 (its <package> tag says no format=\"2\"), which has no <%s>: "
                    "write <package format=\"2\"> (where <%s> is right), or name each dependency as <build_depend> and "
                    "<run_depend>" % (where, ">, <".join(tags), ">, <".join(tags)))
        else:
            hint = ("hint: %s is format %d, which has no <%s>: write <exec_depend> for <run_depend>, or <depend> for a "
                    "package needed to build and to run" % (where, form, ">, <".join(tags)))
        hints.append(causes.finding("package_xml", hint))
    return hints


def _compiled_by(source: str, targets: Dict[str, Target]) -> Target:
    """The target whose object file is made from `source` (`pkg/src/x.cpp`)."""
    for output, target in targets.items():
        if output.endswith(".o") and target.package and source.startswith(target.package + "/") \
                and output.endswith(source[len(target.package) + 1:] + ".o"):
            return target
    return Target(source.split("/", 1)[0] if "/" in source else "", "<target>")


def _missing_header_hint(header: str, package: str, target: Target, own_messages: Set[str]) -> causes.Finding:
    if header in _PLUGINLIB_H:
        return causes.finding(
            "noetic_cxx", "hint: Debian 12's pluginlib has no %s (ROS Noetic's had it; only the course's environment, "
                "`source <course>/catkin_ws/devel/setup.bash`, adds it back): #include <%s>"
                % (header, _PLUGINLIB_H[header]))
    if package in own_messages:
        return causes.finding(
            "no_add_dependencies", "hint: %s is generated from %s's messages, and %s was compiled before it: add "
                "add_dependencies(%s ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS}) after "
                "add_executable(%s ...)" % (header, package, target.name, target.name, target.name))
    return causes.finding(
        "unknown_package", "hint: no package found provides %s: check the spelling, name %s in find_package(catkin "
            "REQUIRED COMPONENTS ...) and as <depend>%s</depend> in package.xml, and keep "
            "include_directories(${catkin_INCLUDE_DIRS})" % (header, package, package))
