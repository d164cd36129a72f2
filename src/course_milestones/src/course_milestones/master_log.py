"""What the master was told, in order: every registration and unregistration of the run.

The master's state (getSystemState) says what is registered now; a node that subscribed for one
message (rospy.wait_for_message, ros::topic::waitForMessage), or that crashed or exited, has left
no trace there, and a check that only looks at the state would say it never subscribed. The
master rostest starts runs inside rostest's own process and logs each call
(`+SUB [/turtle1/pose] /pose_subscriber http://...:41231/`) to
$ROS_LOG_DIR/rostest-<host>-<pid>.log; a check node is rostest's child, so that file is
its parent's. The student's code cannot write it (it is the trusted side's), and it is only read
to say what a node did, never to pass one.
"""
from __future__ import annotations

import glob
import os
import re
from typing import Dict, List, NamedTuple, Optional, Sequence

import rospkg

from course_milestones.discovery import Registration

_LINE = re.compile(r"^\[rosmaster\.master\]\[INFO\] \S+ \S+: (?P<op>[+-])(?P<kind>PUB|SUB|SERVICE) "
                   r"\[(?P<name>[^\]]+)\] (?P<node>\S+) (?P<api>\S+)", re.MULTILINE)
_KINDS = {"PUB": "publishes", "SUB": "subscribes", "SERVICE": "services"}


class Event(NamedTuple):
    added: bool  # + (registered) or - (unregistered)
    kind: str  # "publishes", "subscribes" or "services"
    name: str  # the topic or service
    node: str  # the caller id
    api: str  # the node's XML-RPC URI (a service's rosrpc URI for SERVICE)


def parse(text: str) -> List[Event]:
    """The registration events in a master's log text, in order."""
    return [Event(m.group("op") == "+", _KINDS[m.group("kind")], m.group("name"), m.group("node"), m.group("api"))
            for m in _LINE.finditer(text)]


def ever_registered(events: Sequence[Event], nodes: Optional[Sequence[str]] = None) -> Dict[str, Registration]:
    """Per node (those in `nodes`, else every one): all it ever registered, left or not."""
    found: Dict[str, Dict[str, set]] = {}
    for e in events:
        if e.added and (nodes is None or e.node in nodes):
            found.setdefault(e.node, {k: set() for k in _KINDS.values()})[e.kind].add(e.name)
    return {node: Registration(node, tuple(sorted(k["publishes"])), tuple(sorted(k["subscribes"])),
                               tuple(sorted(k["services"]))) for node, k in found.items()}


def locate(log_dir: Optional[str] = None, rostest_pid: Optional[int] = None) -> Optional[str]:
    """The log of the master of this run: rostest's own log, rostest being our parent."""
    log_dir = log_dir or rospkg.get_log_dir()
    pid = rostest_pid if rostest_pid is not None else os.getppid()
    found = sorted(glob.glob(os.path.join(glob.escape(log_dir), "rostest-*-%d.log" % pid)))
    return found[0] if found else None


class History:
    """The master's log from a mark on: `mark()` before starting a student's node, `since()` after."""

    def __init__(self, path: Optional[str] = None) -> None:
        self.path = path if path is not None else locate()
        self.offset = 0

    def mark(self) -> None:
        self.offset = self._size()

    def since(self) -> List[Event]:
        if not self.path:
            return []
        try:
            with open(self.path, "rb") as f:
                f.seek(self.offset)
                return parse(f.read().decode("utf-8", errors="replace"))
        except OSError:
            return []

    def _size(self) -> int:
        try:
            return os.path.getsize(self.path) if self.path else 0
        except OSError:
            return 0
