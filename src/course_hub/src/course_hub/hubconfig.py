"""JupyterHub's configuration for the course, from the few settings a course changes.

deploy/jupyterhub/jupyterhub_config.py (the one file a course adapts) fills a `HubSettings` and
calls `apply(c, settings)`. What it sets up, and why:

- **Accounts:** the class list (course_hub.classlist) is the hub's allowed users, and nobody else,
  whatever the hub's database remembers; its TAs are the hub's admins (they open any student's
  server). Passwords: FirstUseAuthenticator's file, with every listed user given an initial
  password when the hub starts (course_hub.passwords, the sheet `<data>/initial-passwords.csv`),
  checked by course_hub.auth off the event loop, failed logins limited per name and address.
- **One name, one place:** every place of a user (container, network, disk, folders, server's
  host) comes from course_hub.names; the spawner and the hooks here ask it.
- **Each student a container** of the student image (DockerSpawner, through podman's Docker API),
  running `make jupyter`, which becomes `jupyterhub-singleuser` (course_workbench.startup): in a
  user namespace of its own, without capabilities or new privileges, the image read-only, the
  home and /tmp bounded tmpfs. Removed when the server stops; the student's files are not in it.
- **Its own origin:** the server at `<slug>.<domain>` (`subdomain_host`), so a page the student
  serves cannot act with a TA's hub cookies.
- **A network of their own:** before the spawn, an *internal* bridge network: the container has
  an address on it and no route anywhere else, so A's container cannot open a connection to B's
  (nor reach the internet: the course needs none). The container reaches the hub's API on its
  network's gateway, so the API listens on every address (`hub_ip` 0.0.0.0); `make hub` closes
  that port to the network (course_hub.firewall). podman's `isolate` option was the first
  choice, but netavark 1.4 (Debian 12) drops the firewall's jump to its isolation rules whenever
  any isolated network's container stops (seen here, docs/hub.md).
- **Files:** the user's disk (course_hub.disks: a reserved ext4 image, loop-mounted), whose `src`
  is the container's `~/catkin_ws/src` (it stays when the server stops, is culled or the image
  changes) and whose `grades` is its `~/grades`, read-only (course_hub.grading writes there).
- **Limits:** memory, CPU, processes, disk per container.
- **Culling:** jupyterhub-idle-culler as a hub service stops servers idle for `idle_timeout_s`,
  and any server older than `max_age_s`; the files stay.

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

from course_hub import classlist, disks, names, passwords

# The hub's name on one machine: a dotted name under .localhost (every name there is loopback, for
# browsers and, with libnss-myhostname, for the machine's own programs), so that JupyterHub's
# cookies for the hub and its subdomains have a domain browsers and cookie jars accept.
LOCAL_DOMAIN = "hub.localhost"
STUDENT_HOME = "/home/student"         # the student image's user (docker/Dockerfile)
SRC_IN_CONTAINER = STUDENT_HOME + "/catkin_ws/src"
GRADES_IN_CONTAINER = STUDENT_HOME + "/grades"
DEFAULT_HUB_PORT = 8081
CULLER_SERVICE = "idle-culler"
USERNS = "auto"
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
    bind_url: str = "http://127.0.0.1:8000"         # where the hub's proxy listens (behind TLS for a real class)
    # Each student's server on its own origin, <slug>.<domain>: "auto" is http://hub.localhost:<port>
    # when bind_url is on loopback (*.localhost is loopback); a class sets its public address,
    # with wildcard DNS and a wildcard TLS certificate (docs/hub.md)
    subdomain_host: str = "auto"
    hub_port: int = DEFAULT_HUB_PORT                # the hub's API, which the containers call (all addresses)
    mem_limit: str = "2G"
    cpu_limit: float = 1.0
    pids_limit: int = 1024
    idle_timeout_s: int = 3600
    max_age_s: int = 12 * 3600                      # a server running this long is stopped, active or not
    cull_every_s: int = 300
    disk_limit: str = "1G"                          # each student's disk (course_hub.disks), reserved
    home_limit: str = "512M"                        # the container's writable home and /tmp (memory)
    start_timeout_s: int = 180
    student_uid: int = 1000                         # `student` in the image: owns the folders it writes
    proxy_command: List[str] = field(default_factory=list)  # configurable-http-proxy (make hub's npm prefix)
    password_rounds: int = passwords.DEFAULT_ROUNDS  # bcrypt's cost for the initial passwords


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
    try:
        client.remove_network(place.network)
    except Exception:  # gone already, or still in use by a container being removed: made again at the next spawn
        pass


def mounts(place: names.Places) -> Dict[str, Dict[str, Any]]:
    """DockerSpawner's `volumes` and `read_only_volumes` of the user: their src (`U`: podman
    gives it to the container's user, whichever host uid the user namespace maps it to) and their
    grades (root's on the host, readable by all)."""
    return {"volumes": {place.src: {"bind": SRC_IN_CONTAINER, "mode": "rw,U"}},
            "read_only_volumes": {place.grades: GRADES_IN_CONTAINER}}


def make_hooks(settings: HubSettings):
    """The spawner's pre-spawn and post-stop hooks (disk, folders and network of the user, all
    named by course_hub.names). They are coroutines: the disk and the engine's API calls run in a
    thread, as DockerSpawner's own calls do, so a slow engine never stalls the hub's event loop
    (every other user's page)."""
    disk_size = disks.size_bytes(settings.disk_limit)

    def prepare(spawner: Any, place: names.Places) -> str:
        disks.ensure(place, disk_size, settings.student_uid)
        return ensure_network(spawner.client, place)

    async def pre_spawn(spawner: Any) -> None:
        place = names.places(settings.data_dir, spawner.user.name)
        gateway = await asyncio.get_running_loop().run_in_executor(None, prepare, spawner, place)
        spawner.network_name = place.network
        for trait, value in mounts(place).items():
            setattr(spawner, trait, value)
        spawner.hub_connect_url = "http://%s:%d" % (gateway, urlparse(spawner.hub.api_url).port)

    async def post_stop(spawner: Any) -> None:
        place = names.places(settings.data_dir, spawner.user.name)
        await asyncio.get_running_loop().run_in_executor(None, remove_network, spawner.client, place)

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
    """jupyterhub-idle-culler as a service: idle servers stopped, and any server older than
    `max_age_s` (a server's own token can report activity, so idleness alone is not enough)."""
    return {"name": CULLER_SERVICE,
            "command": [python or sys.executable, "-m", "jupyterhub_idle_culler",
                        "--timeout=%d" % settings.idle_timeout_s, "--max-age=%d" % settings.max_age_s,
                        "--cull-every=%d" % settings.cull_every_s]}


class HubConfigError(ValueError):
    """The course's hub settings cannot make a safe hub; the message says what to set."""


def public_host(settings: HubSettings) -> str:
    """JupyterHub's `subdomain_host`: the hub's public address, under which each user's server has
    a host of its own (course_hub.names.subdomain_hook)."""
    if settings.subdomain_host != "auto":
        if not urlparse(settings.subdomain_host).hostname:
            raise HubConfigError("subdomain_host %r is no address: write the hub's public address, e.g. "
                                 "https://hub.example.org" % settings.subdomain_host)
        return settings.subdomain_host
    bound = urlparse(settings.bind_url)
    if bound.hostname in ("127.0.0.1", "localhost", "::1"):
        default_port = 443 if bound.scheme == "https" else 80
        return "%s://%s%s" % (bound.scheme, LOCAL_DOMAIN, "" if (bound.port or default_port) == default_port
                                     else ":%d" % bound.port)
    raise HubConfigError(
        "the hub listens on %s, not on loopback: set subdomain_host to its public address (e.g. "
        "https://hub.example.org), with wildcard DNS (*.hub.example.org) and a wildcard TLS certificate, "
        "so that each student's server has its own origin (docs/hub.md)" % settings.bind_url)


def lay_out(data: str) -> None:
    """Make the data folder's layout (data_modes) and set its modes, whatever they were."""
    for folder, mode in data_modes(data).items():
        os.makedirs(folder, mode=mode, exist_ok=True)
        os.chmod(folder, mode)


def data_modes(data: str) -> Dict[str, int]:
    """The data folder's layout and modes. Root's alone: the students' disks and mount points, the
    snapshots of every grading; the grader's sandbox user passes through `data` and `grades` to the
    grading under way only (course_hub.grade_cli closes each grading's folder when it is done). The
    hub's own files (database, cookie secret, passwords) are 0600 in `data`."""
    return {data: 0o711, os.path.join(data, "users"): 0o700, os.path.join(data, "disks"): 0o700,
            os.path.join(data, "snapshots"): 0o700, os.path.join(data, "grades"): 0o711}


def host_config(settings: HubSettings) -> Dict[str, Any]:
    """The engine's settings of every student container (docker-py's create_host_config).

    - processes bounded (`pids_limit`);
    - no new privileges and no capabilities: nothing in the container can become root;
    - the image read-only (the course under /course included); what the workbench writes goes to
      the home folder and /tmp, each a tmpfs of `home_limit` counted in the memory limit, so the
      container's writable part is bounded too; catkin_ws/src is on the student's own disk;
    - `auto_remove` off: a container that exits stays until the server is stopped, so that the
      spawner can say why it exited (course_spawner); DockerSpawner removes it then (remove=True).
    """
    tmpfs = "size=%s,mode=%s,nosuid,nodev"
    return {"pids_limit": settings.pids_limit, "auto_remove": False,
            "security_opt": ["no-new-privileges"], "cap_drop": ["ALL"], "read_only": True,
            # U: the home's tmpfs owned by the container's user (podman's option; the image's
            # home is copied into it, as podman does for every tmpfs)
            "tmpfs": {STUDENT_HOME: tmpfs % (settings.home_limit, "0755") + ",U",
                      "/tmp": tmpfs % (settings.home_limit, "1777")}}


CULLER_SCOPES = ["list:users", "read:users:activity", "read:servers", "delete:servers"]


def apply(c: Any, settings: HubSettings) -> classlist.ClassList:
    """Configure JupyterHub's config object `c` for the course; the class list it loaded."""
    users = classlist.load(settings.class_list)
    data = settings.data_dir
    os.makedirs(data, mode=0o700, exist_ok=True)

    lay_out(data)
    c.JupyterHub.bind_url = settings.bind_url
    # every user's server on a host of its own: a page a student serves cannot act with the hub's
    # cookies (a TA's, when the TA opens it)
    c.JupyterHub.subdomain_host = public_host(settings)
    c.JupyterHub.subdomain_hook = names.subdomain_hook
    c.JupyterHub.hub_ip = "0.0.0.0"  # the containers call it through their networks' gateways
    c.JupyterHub.hub_port = settings.hub_port
    c.JupyterHub.db_url = "sqlite:///" + os.path.join(data, "jupyterhub.sqlite")
    c.JupyterHub.cookie_secret_file = os.path.join(data, "jupyterhub_cookie_secret")
    c.ConfigurableHTTPProxy.pid_file = os.path.join(data, "jupyterhub-proxy.pid")
    if settings.proxy_command:
        c.ConfigurableHTTPProxy.command = list(settings.proxy_command)

    # FirstUseAuthenticator's password file, checked off the event loop, failed logins limited,
    # nobody off the class list (course_hub.auth)
    c.JupyterHub.authenticator_class = "course_hub.auth.CourseAuthenticator"
    c.FirstUseAuthenticator.create_users = False
    c.Authenticator.allow_existing_users = False
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
    c.DockerSpawner.remove = True
    c.DockerSpawner.use_internal_ip = True
    # the container's name, network and mounts come from course_hub.names (the spawner, the hooks)
    c.DockerSpawner.mem_limit = settings.mem_limit
    c.DockerSpawner.cpu_limit = settings.cpu_limit
    c.DockerSpawner.extra_host_config = host_config(settings)
    # a user namespace of its own for every container (podman's `auto`: a range of host ids no
    # other running container has, from the `containers` entry of /etc/subuid, which make hub's
    # set-up writes): the student's uid 1000 is no uid of the host's. docker-py refuses the
    # value in create_host_config, so it goes into the request's HostConfig directly.
    c.DockerSpawner.extra_create_kwargs = {"host_config": {"UsernsMode": USERNS}}
    pre_spawn, post_stop = make_hooks(settings)
    c.DockerSpawner.pre_spawn_hook = pre_spawn
    c.DockerSpawner.post_stop_hook = post_stop
    c.Spawner.start_timeout = settings.start_timeout_s
    c.Spawner.http_timeout = settings.start_timeout_s

    c.JupyterHub.services = [culler_service(settings)]
    c.JupyterHub.load_roles = [{"name": CULLER_SERVICE, "scopes": list(CULLER_SCOPES), "services": [CULLER_SERVICE]}]
    return users
