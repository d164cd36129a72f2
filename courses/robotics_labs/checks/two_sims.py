"""The two-turtlesim system of 003 "Launch Files": the student's two_turtles.launch brings up a
turtlesim in /turtlesim1 and one in /turtlesim2 (node names are the student's), so a check
finds each simulator by what it registers in its namespace, not by our node names."""
from __future__ import annotations

from typing import Dict, List, Optional

from course_format import causes
from course_milestones.discovery import MASTER_POLL_S, Registration, system_state
from course_checks.artifacts import save_canvas
from course_checks.waiting import wait_for

NAMESPACES = ("/turtlesim1", "/turtlesim2")
LAUNCH_FILE = "two_turtles.launch"
DEFAULT_BACKGROUND = (69, 86, 255)


def simulators() -> Dict[str, str]:
    """Namespace -> name of the node publishing `<ns>/turtle1/pose` (the turtlesim there)."""
    found = {}
    for node, reg in system_state().items():
        for ns in NAMESPACES:
            if ns + "/turtle1/pose" in reg.publishes:
                found[ns] = node
    return found


def wait_for_simulators(timeout: float) -> Dict[str, str]:
    """simulators() once both namespaces have one, or what there is after `timeout`."""
    def both() -> Dict[str, str]:
        found = simulators()
        return found if len(found) == len(NAMESPACES) else {}
    return wait_for(both, timeout, MASTER_POLL_S) or simulators()


def missing_simulators(found: Dict[str, str]) -> str:
    """A sentence naming the namespaces without a turtlesim (cause wrong_launch), or "" when both have one."""
    missing = [ns for ns in NAMESPACES if ns not in found]
    if not missing:
        return ""
    return causes.finding("wrong_launch", "no turtlesim publishes %s after `roslaunch ... %s` (a turtlesim_node in "
                          "each of the groups turtlesim1 and turtlesim2)"
                          % (" or ".join(ns + "/turtle1/pose" for ns in missing), LAUNCH_FILE))


def readers_of(topic: str, ignore: str) -> List[Registration]:
    """Nodes (other than `ignore`) that subscribe `topic`."""
    return [reg for node, reg in sorted(system_state().items()) if topic in reg.subscribes and node != ignore]


def save_canvases(found: Dict[str, str]) -> None:
    """Each simulator's canvas into the artifacts (turtlesim1.png, turtlesim2.png)."""
    for ns, node in found.items():
        save_canvas(node + "/snapshot", ns.strip("/"))


def colour_of(msg) -> Optional[tuple]:
    return None if msg is None else (msg.r, msg.g, msg.b)
