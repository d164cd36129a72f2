"""What CourseSpawner (course_hub.spawner) asks of the container engine, as plain functions: a
student's own network, their mounts, the engine's settings of their container, and a stopped
container's reason in words. Plain so that the unit tests run them without JupyterHub or
DockerSpawner (against a stand-in engine).

- **A network of their own:** before the spawn, an *internal* bridge network: the container has
  an address on it and no route anywhere else, so A's container cannot open a connection to B's
  (nor reach the internet: the course needs none). The container reaches the hub's API on its
  network's gateway, so the API listens on every address (`hub_ip` 0.0.0.0); `make hub` closes
  that port to the network (course_hub.firewall). podman's `isolate` option was the first
  choice, but netavark 1.4 (Debian 12) drops the firewall's jump to its isolation rules whenever
  any isolated network's container stops (seen here, docs/hub.md).
- **Files:** the user's disk (course_hub.disks), whose `src` is the container's
  `~/catkin_ws/src` and whose `grades` is its `~/grades`, read-only (course_hub.grading writes
  there).
- **Hardening:** no new privileges, no capabilities, the image read-only, the home and /tmp
  bounded tmpfs, processes bounded.
"""
from __future__ import annotations

from typing import Any, Dict, Optional

from course_hub import names
from course_hub.defaults import GRADES_IN_CONTAINER, SRC_IN_CONTAINER, STUDENT_HOME


def ensure_network(client: Any, place: names.Places) -> str:
    """The gateway address of the user's network, made now if missing (`client`: docker's APIClient)."""
    name = place.network
    found = [n for n in client.networks(names=[name]) if n.get("Name") == name]
    if not found:
        # internal: no route off the bridge (no default route in the container, no NAT)
        client.create_network(name, driver="bridge", internal=True, labels={"course-hub.user": place.user})
    info = client.inspect_network(name)
    for config in (info.get("IPAM") or {}).get("Config") or []:
        if config.get("Gateway"):
            return str(config["Gateway"])
    raise RuntimeError("the network %s has no gateway address: the container could not reach the hub" % name)


def remove_network(client: Any, place: names.Places) -> None:
    """Remove the user's network; one gone already, or still in use by a container being removed,
    is left (made again, or found, at the next spawn)."""
    try:
        client.remove_network(place.network)
    except Exception:  # the engine's errors are many (NotFound, APIError 409 ...): none matters here
        pass


def mounts(place: names.Places) -> Dict[str, Dict[str, Any]]:
    """DockerSpawner's `volumes` and `read_only_volumes` of the user: their src (`U`: podman
    gives it to the container's user, whichever host uid the user namespace maps it to) and their
    grades (root's on the host, readable by all)."""
    return {"volumes": {place.src: {"bind": SRC_IN_CONTAINER, "mode": "rw,U"}},
            "read_only_volumes": {place.grades: GRADES_IN_CONTAINER}}


def host_config(pids_limit: int, home_limit: str) -> Dict[str, Any]:
    """The engine's settings of every student container (docker-py's create_host_config).

    - processes bounded (`pids_limit`);
    - no new privileges and no capabilities: nothing in the container can become root;
    - the image read-only (the course under /course included); what the workbench writes goes to
      the home folder and /tmp, each a tmpfs of `home_limit` counted in the memory limit, so the
      container's writable part is bounded too; catkin_ws/src is on the student's own disk;
    - `auto_remove` off: a container that exits stays until the server is stopped, so that the
      spawner can say why it exited; DockerSpawner removes it then (`remove`).
    """
    tmpfs = "size=%s,mode=%s,nosuid,nodev"
    return {"pids_limit": pids_limit, "auto_remove": False,
            "security_opt": ["no-new-privileges"], "cap_drop": ["ALL"], "read_only": True,
            # U: the home's tmpfs owned by the container's user (podman's option; the image's
            # home is copied into it, as podman does for every tmpfs)
            "tmpfs": {STUDENT_HOME: tmpfs % (home_limit, "0755") + ",U",
                      "/tmp": tmpfs % (home_limit, "1777")}}


def exit_reason(state: Dict[str, Any], mem_limit: Optional[str]) -> str:
    """A sentence for a student, from a stopped container's State (Docker's inspect)."""
    code = state.get("ExitCode")
    if state.get("OOMKilled") or code == 137 and mem_limit:
        return ("your server ran out of memory (the course's limit is %s) and was stopped: tell your TA; "
                "your files are safe" % _bytes(mem_limit))
    if state.get("Error"):
        return "your server could not start: %s" % state["Error"]
    return "your server's start-up ended with exit code %s; your files are safe, ask your TA" % code


def _bytes(value: Optional[str]) -> str:
    """A memory size as people write it: 8388608 -> 8M; a size already written so stays."""
    text = str(value or "?")
    if not text.isdigit():
        return text
    number = int(text)
    for unit, size in (("G", 2 ** 30), ("M", 2 ** 20), ("K", 2 ** 10)):
        if number >= size and number % size == 0:
            return "%d%s" % (number // size, unit)
    return text
