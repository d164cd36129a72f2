"""What a course text leaves to the student, as far as it can be seen without running anything of
theirs: which executables a package has (its launch files: course_milestones.launch_files), and
what the master says each running node registered.

A milestone never assumes our reference's script names. It lists the package's executables the
way rosrun would find them and, where the text does not say which is which, starts each one
(course_milestones.students) and asks the master, through this module, what it registered.
"""
from __future__ import annotations

import os
import stat
import time
import xmlrpc.client
from typing import Callable, Dict, Iterable, List, NamedTuple, Optional, Sequence, Set, Tuple

import rosgraph
import rospkg
from catkin.find_in_workspaces import find_in_workspaces

from course_milestones.scripts import node_folders, script_problems
from course_net.rpc import TimedTransport

# Our caller id towards the master, in every query the checks make.
CALLER = "/course_milestone"
# Files rosrun could run that are never a student's node (a dynamic_reconfigure .cfg is an
# executable Python script that generates code). Which folders are searched: scripts.node_folders.
_IGNORED_SUFFIXES = (".pyc", ".so", ".a", ".o", ".cmake", ".txt", ".xml", ".md", ".launch", ".test",
                     ".msg", ".srv", ".action", ".cfg", ".yaml", ".yml", ".png", ".sh~")
_IGNORED_NAMES = {"setup.py", "__init__.py"}
# How often a wait asks the master about registrations: each look costs the check and the master
# 2-4 ms of CPU, and what is waited for (a node starting, a launch file's nodes) takes a second or more.
MASTER_POLL_S = 0.1
# What every rospy node registers: not worth naming to a student.
_ROUTINE = ("/rosout", "/get_loggers", "/set_logger_level")


def package_dir(pkg: str) -> str:
    """Where `pkg` is in the sourced workspaces (an overlay's package shadows the course's)."""
    return rospkg.RosPack().get_path(pkg)


def list_executables(pkg: str) -> List[str]:
    """Paths of the executable files rosrun would find for `pkg` (source folder and devel/lib),
    sorted by name: anywhere in the package (msg/ included) but in the folders
    scripts.node_folders leaves out (build products, the package's tests)."""
    found: Dict[str, str] = {}
    roots = [package_dir(pkg)] + find_in_workspaces(["libexec"], project=pkg, first_matching_workspace_only=True)
    for root in roots:
        for dirpath, filenames in node_folders(root):
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


def launch_file_names(pkg: str) -> List[str]:
    """Names of the .launch files anywhere in `pkg` (what `roslaunch pkg <TAB>` offers)."""
    found = []
    for dirpath, dirnames, filenames in os.walk(package_dir(pkg)):
        dirnames[:] = [d for d in dirnames if not d.startswith(".")]
        found.extend(f for f in filenames if f.endswith(".launch"))
    return sorted(set(found))


def script_hints(pkg: str) -> str:
    """Why rosrun may not find the student's nodes, for a message saying no executable of `pkg` did
    what was asked: ' (a.py starts with #! but is not executable ...)' when some scripts cannot be
    started (course_milestones.scripts says why), and the package's launch files when it has any
    (the text runs these nodes with rosrun: a launch file alone is not what it asks); else ''."""
    problems = script_problems(package_dir(pkg))
    launches = launch_file_names(pkg)
    if launches:
        problems.append("the package's launch files (%s) are not started: the text runs these nodes with "
                        "`rosrun %s <script>`, so each must be an executable of the package" % (", ".join(launches), pkg))
    return " (%s)" % "; ".join(problems) if problems else ""


def unbuilt_problems(pkg: str) -> List[str]:
    """What `pkg` holds but the space that built it did not make (course_milestones.unbuilt): its
    messages, services and actions without generated code, its Python modules not installed."""
    from course_milestones import messages, unbuilt  # messages needs genmsg: only when asked
    try:
        folder = package_dir(pkg)
    except rospkg.ResourceNotFound:
        return []
    return unbuilt.problems(folder, pkg, messages.built_space(pkg) or os.devnull)


def describe(names: Sequence[str]) -> str:
    """A short list of executable names for messages to the student."""
    return ", ".join(os.path.basename(n) for n in names) or "(none)"


class Registration(NamedTuple):
    """What one node registered with the master."""

    node: str
    publishes: Tuple[str, ...]
    subscribes: Tuple[str, ...]
    services: Tuple[str, ...]


def own_names(names: Iterable[str]) -> List[str]:
    """`names` (topics, services) without those every rospy node registers."""
    return [n for n in names if not n.endswith(_ROUTINE)]


def publishes(topic: str) -> Callable[[Registration], bool]:
    return lambda reg: topic in reg.publishes


def subscribes(topic: str) -> Callable[[Registration], bool]:
    return lambda reg: topic in reg.subscribes


def system_state(caller_id: str = CALLER) -> Dict[str, Registration]:
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


def registrations_with_uris() -> List[Tuple[Registration, str]]:
    """Every registered node with its XML-RPC URI (nodes that went away meanwhile are left out).
    A node started under a name already taken replaces the old one: the name stays, the URI
    changes, so a node is told apart from its predecessor by URI."""
    master = rosgraph.Master(CALLER)
    found = []
    for node, reg in system_state().items():
        try:
            found.append((reg, master.lookupNode(node)))
        except Exception:  # noqa: BLE001 - the node went away meanwhile
            continue
    return found


def node_uris() -> Dict[str, str]:
    """Every registered node's name -> XML-RPC URI."""
    return {reg.node: uri for reg, uri in registrations_with_uris()}


def new_registrations(before: Dict[str, str]) -> List[Registration]:
    """Registrations of nodes that were not in `before` (name -> URI), or are there under a new URI."""
    return [reg for reg, uri in registrations_with_uris() if before.get(reg.node) != uri]


def new_nodes(before: Iterable[str], caller_id: str = CALLER) -> Dict[str, Registration]:
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


NODE_CALL_TIMEOUT_S = 2.0


def sends_to(node_uri: str, topic: str, subscriber: str) -> Optional[bool]:
    """Whether the node at `node_uri` has an outbound connection on `topic` to the node named
    `subscriber`, by its own bus info (the slave API's getBusInfo: rospy and roscpp list each
    publication's connections with the subscriber's caller id). None when it cannot tell: no
    answer, or an answer not in that form.

    A subscriber counts its connection once the publisher's handshake reply has arrived; the
    publisher counts it a moment later (rospy replies, then adds the connection): a message
    published in between reaches nobody."""
    try:
        code, _, info = xmlrpc.client.ServerProxy(node_uri, transport=TimedTransport(NODE_CALL_TIMEOUT_S)
                                                  ).getBusInfo(CALLER)
    except Exception:  # noqa: BLE001 - the node's answer may be anything (bad XML, a dropped line, no server)
        return None
    if code != 1 or not isinstance(info, list):
        return None
    return any(isinstance(c, list) and len(c) >= 5 and c[1] == subscriber and c[2] == "o" and c[4] == topic
               for c in info)


def published_type(node_uri: str, topic: str) -> Optional[str]:
    """The message type the node at `node_uri` publishes `topic` with, by its own word (the slave
    API's getPublications). The master keeps the first type registered for a topic, a subscriber's
    too (a check's recorder that subscribed first): only the node says what it sends. None when
    it does not publish the topic or cannot tell."""
    try:
        code, _, publications = xmlrpc.client.ServerProxy(
            node_uri, transport=TimedTransport(NODE_CALL_TIMEOUT_S)).getPublications(CALLER)
    except Exception:  # noqa: BLE001 - the node's answer may be anything (bad XML, a dropped line, no server)
        return None
    if code != 1 or not isinstance(publications, list):
        return None
    return next((p[1] for p in publications if isinstance(p, list) and len(p) == 2 and p[0] == topic
                 and isinstance(p[1], str)), None)


def topic_types(caller_id: str = CALLER) -> Dict[str, str]:
    """Topic name -> message type as the master knows it (the publisher's declared type)."""
    return dict(rosgraph.Master(caller_id).getTopicTypes())
