"""A student's launch files as roslaunch reads them: which a package has, where `roslaunch PKG FILE`
finds one, which parameters it sets and how it starts a node, without running it (running it:
course_milestones.students.Roslaunch).

The launch milestones run the student's file exactly as the text's command does (no extra args);
this module lets them also start one of its nodes again by itself, with other parameter values,
to see whether the node really uses them (001 #2.3.7).
"""
from __future__ import annotations

import os
import shlex
from typing import Dict, List, Optional, Tuple

import roslaunch.config
import roslaunch.core
import roslaunch.rlutil
import rosgraph.names

from course_milestones.discovery import package_dir
from course_testkit.nodes import find_executable


def names_in(pkg: str) -> List[str]:
    """Names of the .launch files anywhere in `pkg` (what `roslaunch pkg <TAB>` offers)."""
    found = []
    for dirpath, dirnames, filenames in os.walk(package_dir(pkg)):
        dirnames[:] = [d for d in dirnames if not d.startswith(".")]
        found.extend(f for f in filenames if f.endswith(".launch"))
    return sorted(set(found))


def missing_launch_file(pkg: str, filename: str) -> str:
    """A sentence for the student when `filename` is not in `pkg`, or "" when it is."""
    found = names_in(pkg)
    if filename in found:
        return ""
    return "no launch file %s in package %s (found: %s)" % (filename, pkg, ", ".join(found) or "none")


def resolve(pkg: str, name: str) -> Tuple[Optional[str], str]:
    """The path `roslaunch PKG NAME` would run, or None and roslaunch's reason."""
    try:
        return roslaunch.rlutil.resolve_launch_arguments([pkg, name])[0], ""
    except (roslaunch.core.RLException, IndexError) as err:
        return None, str(err)


def load(path: str) -> roslaunch.config.ROSLaunchConfig:
    """The launch file's nodes and parameters (roslaunch's own parser; raises RLException)."""
    return roslaunch.config.load_config_default([path], None)


ROSLAUNCH_OWN = ("/rosdistro", "/rosversion", "/run_id")


def params(config: roslaunch.config.ROSLaunchConfig) -> Dict[str, object]:
    """Every parameter the file sets (global, in groups and private to its nodes), not roslaunch's own."""
    return {key: p.value for key, p in config.params.items() if key not in ROSLAUNCH_OWN}


def params_named(config: roslaunch.config.ROSLaunchConfig, basename: str) -> Dict[str, object]:
    """Every parameter the file sets whose last name part is `basename` (global or private)."""
    return {key: p.value for key, p in config.params.items() if key.rstrip("/").split("/")[-1] == basename}


def params_with_value(config: roslaunch.config.ROSLaunchConfig, values: Tuple[str, ...]) -> Dict[str, object]:
    """Parameters whose value is one of `values` (e.g. a topic name)."""
    return {key: p.value for key, p in config.params.items() if isinstance(p.value, str) and p.value in values}


def node_named(config: roslaunch.config.ROSLaunchConfig, resolved: str) -> Optional[roslaunch.core.Node]:
    """The launch file's node whose full name is `resolved` (e.g. '/mybot_teleop')."""
    for node in config.nodes:
        if rosgraph.names.ns_join(node.namespace or "/", node.name) == resolved:
            return node
    return None


def node_command(node: roslaunch.core.Node) -> Tuple[List[str], Dict[str, str]]:
    """The command and extra environment that start `node` as roslaunch would (name, namespace,
    arguments and remappings; parameters come from the parameter server)."""
    command = [find_executable(node.package, node.type)] + shlex.split(node.args or "")
    command += ["%s:=%s" % tuple(pair) for pair in node.remap_args] + ["__name:=%s" % node.name]
    env = {"ROS_NAMESPACE": node.namespace} if node.namespace and node.namespace != "/" else {}
    env.update({k: v for k, v in (node.env_args or [])})
    return command, env
