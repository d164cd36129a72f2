"""A student's launch files as roslaunch reads them: which a package has, where `roslaunch PKG FILE`
finds one, which parameters it sets and how it starts a node, without running it (running it:
course_milestones.students.Roslaunch).

The launch milestones run the student's file exactly as the text's command does (no extra args);
this module lets them also start one of its nodes again by itself, with other parameter values,
to see whether the node really uses them (001 #2.3.7).

Loading a launch file runs the student's code ($(eval) is Python, <param command> a shell
command, textfile/binfile/rosparam file read any file), and a check runs with the grader's
rights. So `load` never loads it here: `python3 -m course_milestones.launch_dump` does, in a
process started through the students' sandbox (students.run_captured), and prints JSON that this
module reads as untrusted data: bounded in size, every field's type checked, anything else a
LaunchFileError whose message is a sentence for the student.
"""
from __future__ import annotations

import json
import os
import re
import shlex
import sys
from typing import Dict, List, NamedTuple, Optional, Sequence, Tuple

import roslaunch.core
import roslaunch.rlutil
import rosgraph.names

from course_format import causes
from course_milestones import students
from course_milestones.discovery import launch_file_names, package_dir
from course_milestones.launch_dump import FORMAT
from course_checks.nodes import find_executable

LOAD_TIMEOUT_S = 30.0          # roslaunch reads a file in about a second; a <param command> may hang
MAX_DUMP_BYTES = 1024 * 1024   # what students.run_captured keeps of the output
ROSLAUNCH_OWN = ("/rosdistro", "/rosversion", "/run_id")
_PACKAGE = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


class LaunchFileError(roslaunch.core.RLException):
    """Why a launch file cannot be read, as a sentence (an RLException, as roslaunch's own errors were)."""


class LaunchNode(NamedTuple):
    """A <node> of a launch file, with the attributes of roslaunch.core.Node the checks use."""

    package: str
    type: str
    name: str
    namespace: str
    args: str
    remap_args: Tuple[Tuple[str, str], ...]
    env_args: Tuple[Tuple[str, str], ...]


class LaunchConfig(NamedTuple):
    """What a launch file sets and starts: every parameter by full name (roslaunch's own
    /rosdistro, /rosversion and /run_id included, as roslaunch has them), and its nodes."""

    params: Dict[str, object]
    nodes: Tuple[LaunchNode, ...]


def missing_launch_file(pkg: str, filename: str) -> str:
    """A sentence for the student when `filename` is not in `pkg` (cause not_started), or "" when it is."""
    found = launch_file_names(pkg)
    if filename in found:
        return ""
    return causes.finding("not_started", "no launch file %s in package %s (found: %s)" % (filename, pkg,
                                                                                       ", ".join(found) or "none"))


def resolve(pkg: str, name: str) -> Tuple[Optional[str], str]:
    """The path `roslaunch PKG NAME` would run, or None and roslaunch's reason (finding the file
    reads folders only: nothing of the student's runs)."""
    try:
        return roslaunch.rlutil.resolve_launch_arguments([pkg, name])[0], ""
    except (roslaunch.core.RLException, IndexError) as err:
        return None, str(err)


def load(path: str, args: Sequence[str] = ()) -> LaunchConfig:
    """The launch file's nodes and parameters, as roslaunch's own parser reads them with the
    roslaunch args `args` (`name:=value`), read in a sandboxed process (see the module's
    docstring). Raises LaunchFileError."""
    argv = [sys.executable, "-P", "-m", "course_milestones.launch_dump", path] + list(args)
    code, output = students.run_captured(argv, timeout=LOAD_TIMEOUT_S)
    return parse_dump(code, output, os.path.basename(path))


def parse_dump(code: Optional[int], output: bytes, what: str = "the launch file") -> LaunchConfig:
    """launch_dump's answer (exit code and stdout), checked as untrusted data. Raises
    LaunchFileError with a sentence for the student."""
    if code is None:
        raise LaunchFileError("reading %s took more than %.0f s (a <param command=...> or $(eval ...) that never "
                              "ends?)" % (what, LOAD_TIMEOUT_S))
    if not isinstance(output, bytes) or len(output) >= MAX_DUMP_BYTES:
        raise LaunchFileError("%s sets more than %d bytes of parameters and nodes: too much to check"
                              % (what, MAX_DUMP_BYTES))
    try:
        answer = json.loads(output.decode("utf-8"))
    except (ValueError, RecursionError):  # UnicodeDecodeError and JSONDecodeError are ValueErrors
        answer = None
    if not isinstance(answer, dict) or answer.get("format") != FORMAT:
        raise LaunchFileError("roslaunch could not read %s (its loader ended with code %s and no answer)"
                              % (what, code))
    if "error" in answer:
        error = answer["error"]
        reason = " ".join(error.split())[:500] if isinstance(error, str) else "no reason given"
        raise LaunchFileError("roslaunch cannot load %s: %s" % (what, reason))
    if code != 0:
        raise LaunchFileError("roslaunch could not read %s (its loader ended with code %s)" % (what, code))
    params, nodes = answer.get("params"), answer.get("nodes")
    if not isinstance(params, dict) or not all(isinstance(k, str) and k.startswith("/") for k in params):
        raise LaunchFileError("the parameters read from %s are not a table of /names" % what)
    if not isinstance(nodes, list):
        raise LaunchFileError("the nodes read from %s are not a list" % what)
    return LaunchConfig(dict(params), tuple(_node(n, i, what) for i, n in enumerate(nodes)))


def _node(data: object, index: int, what: str) -> LaunchNode:
    """One node of the dump, every field's type checked."""
    def bad(reason: str) -> LaunchFileError:
        return LaunchFileError("node %d read from %s: %s" % (index + 1, what, reason))
    if not isinstance(data, dict):
        raise bad("not a table")
    text = {}
    for key in ("package", "type", "name", "namespace", "args"):
        value = data.get(key)
        if not isinstance(value, str) or "\0" in value:
            raise bad("its %s is not text" % key)
        text[key] = value
    if not _PACKAGE.match(text["package"]):
        raise bad("%r is not a package name" % text["package"])
    if not text["type"] or "/" in text["type"] or text["type"] in (".", ".."):
        raise bad("%r is not an executable's name" % text["type"])
    pairs = {}
    for key in ("remap_args", "env_args"):
        value = data.get(key)
        if not isinstance(value, list) or not all(isinstance(p, list) and len(p) == 2
                                                  and all(isinstance(s, str) for s in p) for p in value):
            raise bad("its %s are not pairs of text" % key)
        pairs[key] = tuple((a, b) for a, b in value)
    return LaunchNode(text["package"], text["type"], text["name"], text["namespace"], text["args"],
                      pairs["remap_args"], pairs["env_args"])


def params(config: LaunchConfig) -> Dict[str, object]:
    """Every parameter the file sets (global, in groups and private to its nodes), not roslaunch's own."""
    return {key: value for key, value in config.params.items() if key not in ROSLAUNCH_OWN}


def params_named(config: LaunchConfig, basename: str) -> Dict[str, object]:
    """Every parameter the file sets whose last name part is `basename` (global or private)."""
    return {key: value for key, value in config.params.items() if key.rstrip("/").split("/")[-1] == basename}


def params_with_value(config: LaunchConfig, values: Tuple[str, ...]) -> Dict[str, object]:
    """Parameters whose value is one of `values` (e.g. a topic name)."""
    return {key: value for key, value in config.params.items() if isinstance(value, str) and value in values}


def node_named(config: LaunchConfig, resolved: str) -> Optional[LaunchNode]:
    """The launch file's node whose full name is `resolved` (e.g. '/mybot_teleop')."""
    for node in config.nodes:
        if rosgraph.names.ns_join(node.namespace or "/", node.name) == resolved:
            return node
    return None


def node_command(node: LaunchNode) -> Tuple[List[str], Dict[str, str]]:
    """The command and extra environment that start `node` as roslaunch would (name, namespace,
    arguments and remappings; parameters come from the parameter server)."""
    command = [find_executable(node.package, node.type)] + shlex.split(node.args or "")
    command += ["%s:=%s" % tuple(pair) for pair in node.remap_args] + ["__name:=%s" % node.name]
    env = {"ROS_NAMESPACE": node.namespace} if node.namespace and node.namespace != "/" else {}
    env.update({k: v for k, v in (node.env_args or [])})
    return command, env
