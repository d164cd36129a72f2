"""Find what a course text leaves to the student: which executables a package has, and which of
them publishes, subscribes or serves what once it runs.

A milestone never assumes our reference's script names. It lists the package's executables the
way rosrun would find them and, where the text does not say which is which, starts each one and
asks the master what it registered.
"""
from __future__ import annotations

import os
import stat
import time
from typing import Callable, Dict, Iterable, List, NamedTuple, Optional, Sequence, Set, Tuple

import rosgraph
import rospkg
from catkin.find_in_workspaces import find_in_workspaces

# Files rosrun could run that are never a student's node.
_IGNORED_SUFFIXES = (".pyc", ".so", ".a", ".o", ".cmake", ".txt", ".xml", ".md", ".launch", ".test",
                     ".msg", ".srv", ".action", ".yaml", ".yml", ".png", ".sh~")
_IGNORED_DIRS = {"CMakeFiles", ".git", "__pycache__", "test", "tests", "msg", "srv", "action", "cfg"}
_IGNORED_NAMES = {"setup.py", "__init__.py"}


def package_dir(pkg: str) -> str:
    """Where `pkg` is in the sourced workspaces (an overlay's package shadows the course's)."""
    return rospkg.RosPack().get_path(pkg)


def list_executables(pkg: str) -> List[str]:
    """Paths of the executable files rosrun would find for `pkg` (source folder and devel/lib),
    sorted by name; scripts in a package's test folders are left out."""
    found: Dict[str, str] = {}
    roots = [package_dir(pkg)] + find_in_workspaces(["libexec"], project=pkg, first_matching_workspace_only=True)
    for root in roots:
        for dirpath, dirnames, filenames in os.walk(root):
            dirnames[:] = [d for d in dirnames if d not in _IGNORED_DIRS and not d.startswith(".")]
            for name in filenames:
                path = os.path.join(dirpath, name)
                if name in _IGNORED_NAMES or name.endswith(_IGNORED_SUFFIXES) or not _is_executable(path):
                    continue
                found.setdefault(name, path)
    return [found[n] for n in sorted(found)]


def _is_executable(path: str) -> bool:
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return False
    return stat.S_ISREG(mode) and bool(mode & (stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH))


class Registration(NamedTuple):
    """What one node registered with the master."""

    node: str
    publishes: Tuple[str, ...]
    subscribes: Tuple[str, ...]
    services: Tuple[str, ...]


def system_state(caller_id: str = "/course_milestone") -> Dict[str, Registration]:
    """Every node's publications, subscriptions and services, from the master."""
    pubs, subs, srvs = rosgraph.Master(caller_id).getSystemState()
    table: Dict[str, Dict[str, Set[str]]] = {}
    for kind, entries in (("publishes", pubs), ("subscribes", subs), ("services", srvs)):
        for name, nodes in entries:
            for node in nodes:
                table.setdefault(node, {"publishes": set(), "subscribes": set(), "services": set()})[kind].add(name)
    return {node: Registration(node, tuple(sorted(k["publishes"])), tuple(sorted(k["subscribes"])),
                               tuple(sorted(k["services"])))
            for node, k in table.items()}


def new_nodes(before: Iterable[str], caller_id: str = "/course_milestone") -> Dict[str, Registration]:
    """Nodes registered now that were not in `before`."""
    known = set(before)
    return {n: r for n, r in system_state(caller_id).items() if n not in known}


def wait_for_registration(before: Iterable[str], condition: Callable[[Registration], bool], timeout: float,
                          still_running: Callable[[], bool] = lambda: True) -> Optional[Registration]:
    """The first new node (not in `before`) whose registration satisfies `condition`, or None once
    `timeout` passes or the process under test exits. rospy registers each publisher, subscriber and
    service as it is created, so this waits for the whole set the condition asks for."""
    deadline = time.monotonic() + timeout
    while True:
        for reg in new_nodes(before).values():
            if condition(reg):
                return reg
        if time.monotonic() > deadline or not still_running():
            return None
        time.sleep(0.05)


def topic_types(caller_id: str = "/course_milestone") -> Dict[str, str]:
    """Topic name -> message type as the master knows it (the publisher's declared type)."""
    return dict(rosgraph.Master(caller_id).getTopicTypes())


def describe(names: Sequence[str]) -> str:
    """A short list of executable names for messages to the student."""
    return ", ".join(os.path.basename(n) for n in names) or "(none)"
