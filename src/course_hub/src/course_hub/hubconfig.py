"""JupyterHub's configuration for the course, from the few settings a course changes.

deploy/jupyterhub/jupyterhub_config.py (the one file a course adapts) fills a `HubSettings` and
calls `apply(c, settings)`. What it sets up, and why:

- **Accounts:** the class list (course_hub.classlist) is the hub's allowed users; its TAs are the
  hub's admins (JupyterHub's `admin` role: they open any student's server, `/user/<name>/`).
  Passwords: FirstUseAuthenticator, with every listed user given an initial password when the hub
  starts (course_hub.passwords: its hash in the authenticator's file, the password on the sheet
  `<data>/initial-passwords.csv` the instructor hands out), so nobody can claim a classmate's
  name by logging in first; `/hub/auth/change-password` changes it, and `make hub-password
  RESET=<user>` is an admin's reset (docs/hub.md).
- **Each student a container** of the student image (DockerSpawner, through the engine's Docker
  API: podman's `system service` here), running `make jupyter`, which becomes
  `jupyterhub-singleuser` under a hub (course_workbench.startup). The container is removed when the
  server stops; the student's files are not in it.
- **A network of their own:** before the spawn, an *internal* bridge network
  `course-hub-net-<user>`: the container has an address on it and no route anywhere else, so A's
  container cannot open a connection to B's, whatever port B's processes listen on (and cannot
  reach the internet: the course needs none). The hub's host reaches the container on its
  network's address; the container reaches the hub's API on its network's gateway (the host's
  own address on that bridge; the API listens on every address, `hub_ip` 0.0.0.0, and answers only
  with a token). podman's `isolate` option was the first choice, but netavark 1.4 (Debian 12)
  drops the firewall's jump to its isolation rules whenever any isolated network's container
  stops, which left the other students' networks open (seen here, docs/hub.md).
- **Files:** `<data>/users/<user>/src` is the container's `~/catkin_ws/src` (persistent: it stays
  when the server stops, is culled or the image changes), and `<data>/users/<user>/grades` its
  `~/grades`, read-only: the reports grading from the hub copies there (course_hub.grading).
- **Limits:** memory, CPU and processes per container.
- **Idle culling:** jupyterhub-idle-culler as a hub service stops servers idle for
  `idle_timeout_s`; the files stay.

This module never imports jupyterhub or dockerspawner at import time: its plain parts (the
settings, names, folders) are unit-tested without them.
"""
from __future__ import annotations

import asyncio
import os
import sys
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional
from urllib.parse import urlparse

from course_hub import classlist, passwords

NAME_PREFIX = "course-hub-"            # containers course-hub-<user>, networks course-hub-net-<user>
STUDENT_HOME = "/home/student"         # the student image's user (docker/Dockerfile)
SRC_IN_CONTAINER = STUDENT_HOME + "/catkin_ws/src"
GRADES_IN_CONTAINER = STUDENT_HOME + "/grades"
CULLER_SERVICE = "idle-culler"
# What `make jupyter` runs, exec'd down to the server itself (bash, rosrun, the start-up, then
# jupyterhub-singleuser): the server is the container's main process, so the container ends with
# the server's own exit status (137 when the memory limit killed it) and not make's 2.
SINGLEUSER_COMMAND = ("bash", "-c", "source catkin_ws/devel/setup.bash && exec rosrun course_workbench workbench")


@dataclass
class HubSettings:
    """What a course sets (deploy/jupyterhub/jupyterhub_config.py); defaults for one machine."""

    class_list: str                                 # the CSV of users (course_hub.classlist)
    data_dir: str = "/var/lib/ros-course-hub"       # users' folders, the hub's database and secrets
    image: str = "localhost/ros-course"             # the student image (docker/Dockerfile's default target)
    bind_url: str = "http://127.0.0.1:8000"         # where students open the hub (behind TLS for a real class)
    hub_port: int = 8081                            # the hub's API, which the containers call (all addresses)
    mem_limit: str = "2G"
    cpu_limit: float = 1.0
    pids_limit: int = 1024
    idle_timeout_s: int = 3600
    cull_every_s: int = 300
    start_timeout_s: int = 180
    student_uid: int = 1000                         # `student` in the image: owns the folders it writes
    proxy_command: List[str] = field(default_factory=list)  # configurable-http-proxy (make hub's npm prefix)
    password_rounds: int = passwords.DEFAULT_ROUNDS  # bcrypt's cost for the initial passwords


def network_name(user: str) -> str:
    return "%snet-%s" % (NAME_PREFIX, user)


def user_folders(data_dir: str, user: str) -> Dict[str, str]:
    """The host's folders of `user`: `src` (their catkin_ws/src) and `grades` (their reports)."""
    base = os.path.join(data_dir, "users", user)
    return {"src": os.path.join(base, "src"), "grades": os.path.join(base, "grades")}


def ensure_user_folders(data_dir: str, user: str, uid: int) -> Dict[str, str]:
    """Create `user`'s folders if missing: src owned by the image's student (uid), grades readable
    by them and writable by the hub (root) only. Modes are set explicitly: the hub runs with
    umask 077 (course_hub.runner)."""
    folders = user_folders(data_dir, user)
    if not os.path.isdir(folders["src"]):
        os.makedirs(folders["src"])
        os.chown(folders["src"], uid, uid)
        os.chmod(folders["src"], 0o755)
    os.makedirs(folders["grades"], exist_ok=True)
    os.chmod(folders["grades"], 0o755)
    return folders


def ensure_network(client: Any, user: str) -> str:
    """The gateway address of `user`'s network, made now if missing (`client`: docker's APIClient)."""
    name = network_name(user)
    found = [n for n in client.networks(names=[name]) if n.get("Name") == name]
    if not found:
        # internal: no route off the bridge (no default route in the container, no NAT)
        client.create_network(name, driver="bridge", internal=True, labels={"course-hub.user": user})
    info = client.inspect_network(name)
    for config in (info.get("IPAM") or {}).get("Config") or []:
        if config.get("Gateway"):
            return str(config["Gateway"])
    raise RuntimeError("the network %s has no gateway address: the container could not reach the hub" % name)


def remove_network(client: Any, user: str) -> None:
    try:
        client.remove_network(network_name(user))
    except Exception:  # gone already, or still in use by a container being removed: made again at the next spawn
        pass


def make_hooks(settings: HubSettings):
    """The spawner's pre-spawn and post-stop hooks (folders and network of the user). They are
    coroutines: the engine's API calls run in a thread, as DockerSpawner's own do, so a slow
    engine never stalls the hub's event loop (every other user's page)."""

    def prepare(spawner: Any) -> str:
        ensure_user_folders(settings.data_dir, spawner.user.name, settings.student_uid)
        return ensure_network(spawner.client, spawner.user.name)

    async def pre_spawn(spawner: Any) -> None:
        gateway = await asyncio.get_running_loop().run_in_executor(None, prepare, spawner)
        spawner.network_name = network_name(spawner.user.name)
        spawner.hub_connect_url = "http://%s:%d" % (gateway, urlparse(spawner.hub.api_url).port)

    async def post_stop(spawner: Any) -> None:
        await asyncio.get_running_loop().run_in_executor(None, remove_network, spawner.client, spawner.user.name)

    return pre_spawn, post_stop


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


def culler_service(settings: HubSettings, python: Optional[str] = None) -> Dict[str, Any]:
    return {"name": CULLER_SERVICE,
            "command": [python or sys.executable, "-m", "jupyterhub_idle_culler",
                        "--timeout=%d" % settings.idle_timeout_s, "--cull-every=%d" % settings.cull_every_s]}


CULLER_SCOPES = ["list:users", "read:users:activity", "read:servers", "delete:servers"]


def apply(c: Any, settings: HubSettings) -> classlist.ClassList:
    """Configure JupyterHub's config object `c` for the course; the class list it loaded."""
    users = classlist.load(settings.class_list)
    data = settings.data_dir
    os.makedirs(data, mode=0o700, exist_ok=True)

    os.chmod(data, 0o711)  # the grader's sandbox user passes through to the grades (secrets are 0600)
    c.JupyterHub.bind_url = settings.bind_url
    c.JupyterHub.hub_ip = "0.0.0.0"  # the containers call it through their networks' gateways
    c.JupyterHub.hub_port = settings.hub_port
    c.JupyterHub.db_url = "sqlite:///" + os.path.join(data, "jupyterhub.sqlite")
    c.JupyterHub.cookie_secret_file = os.path.join(data, "jupyterhub_cookie_secret")
    c.ConfigurableHTTPProxy.pid_file = os.path.join(data, "jupyterhub-proxy.pid")
    if settings.proxy_command:
        c.ConfigurableHTTPProxy.command = list(settings.proxy_command)

    c.JupyterHub.authenticator_class = "firstuseauthenticator.FirstUseAuthenticator"
    c.FirstUseAuthenticator.create_users = False
    c.FirstUseAuthenticator.dbm_path = passwords.dbm_of(data)
    sheet = passwords.sheet_of(data)
    given = passwords.seed(c.FirstUseAuthenticator.dbm_path, users, sheet, settings.password_rounds)
    if given:
        print("course hub: initial passwords for %d user(s) (%s) added to %s: hand them out"
              % (len(given), ", ".join(name for name, _ in given), sheet), file=sys.stderr)
    c.Authenticator.allowed_users = set(users.users)
    c.Authenticator.admin_users = set(users.admins)

    # DockerSpawner, saying why a server stopped (deploy/jupyterhub/course_spawner.py, on the hub's path)
    c.JupyterHub.spawner_class = "course_spawner.CourseSpawner"
    c.DockerSpawner.image = settings.image
    c.DockerSpawner.pull_policy = "never"  # no registry: the image is built on this machine
    c.DockerSpawner.cmd = list(SINGLEUSER_COMMAND)
    c.DockerSpawner.name_template = NAME_PREFIX + "{username}"
    c.DockerSpawner.remove = True
    c.DockerSpawner.use_internal_ip = True
    c.DockerSpawner.volumes = {user_folders(data, "{username}")["src"]: SRC_IN_CONTAINER}
    c.DockerSpawner.read_only_volumes = {user_folders(data, "{username}")["grades"]: GRADES_IN_CONTAINER}
    c.DockerSpawner.mem_limit = settings.mem_limit
    c.DockerSpawner.cpu_limit = settings.cpu_limit
    # auto_remove off: a container that exits stays until the server is stopped, so that the
    # spawner can say why it exited (course_spawner); DockerSpawner removes it then (remove=True)
    c.DockerSpawner.extra_host_config = {"pids_limit": settings.pids_limit, "auto_remove": False}
    pre_spawn, post_stop = make_hooks(settings)
    c.DockerSpawner.pre_spawn_hook = pre_spawn
    c.DockerSpawner.post_stop_hook = post_stop
    c.Spawner.start_timeout = settings.start_timeout_s
    c.Spawner.http_timeout = settings.start_timeout_s

    c.JupyterHub.services = [culler_service(settings)]
    c.JupyterHub.load_roles = [{"name": CULLER_SERVICE, "scopes": list(CULLER_SCOPES), "services": [CULLER_SERVICE]}]
    return users
