"""CourseSpawner: DockerSpawner for the ROS course, each student a hardened container of the
student image, configured as JupyterHub's own plug-ins are, by traits:

    c.JupyterHub.spawner_class = "course_hub.spawner.CourseSpawner"   # or its entry point, "course"
    c.CourseSpawner.data_dir = "/var/lib/ros-course-hub"
    c.CourseSpawner.image = "localhost/ros-course"
    c.CourseSpawner.mem_limit = "2G"                                   # DockerSpawner's own traits too

What it adds to DockerSpawner, and why:

- **One name, one place:** the container, the network, the disk and the folders of a user are
  all named by course_hub.names (DockerSpawner's own templates escape a name their own way:
  users `a-b` and `a-2db` once shared a folder).
- **A disk and a network of their own**, made before the container starts
  (course_hub.disks, course_hub.containers): the kernel bounds what a student keeps, and their
  container has no route off its own internal bridge but the hub's API on its gateway. The
  network goes when the server stops; the disk stays.
- **Hardened:** a user namespace of its own, no capabilities, no new privileges, the image
  read-only, the home and /tmp bounded tmpfs (`extra_host_config`'s default: extend it with
  `c.CourseSpawner.extra_host_config.update({...})`, which keeps these).
- **Says why a server stopped:** DockerSpawner's poll reports a stopped container as
  `ExitCode=137, Error='', FinishedAt=...`, and JupyterHub shows that string to the student.
  This one says what happened (out of memory under the course's limit, or the start-up's exit
  code). The container must still be there to be asked, so the engine does not remove it when
  it exits (`auto_remove` off); DockerSpawner removes it when the server stops (`remove`).
- **Waits for the server** in `start` until it accepts connections on its port or its container
  stops: a server that dies while starting fails the spawn with that sentence, which the student
  reads on the spawn page (JupyterHub's own wait for the server's HTTP answer was seen taking a
  server killed by its memory limit for a running one).

Loading the configuration does nothing but set traits: the data folder and the disks are made
when the hub starts (course_hub.runner) and at each spawn.
"""
from __future__ import annotations

import asyncio
import copy
import time
from typing import Any, Dict, List, Optional, Tuple
from urllib.parse import urlparse

from dockerspawner import DockerSpawner
from traitlets import Integer, TraitError, Unicode, default, validate

from course_hub import containers, defaults, disks, layout, names

CONNECT_TIMEOUT_S = 2.0
LOOK_EVERY_S = 0.5


def _course_default(trait: str, value: Any) -> Any:
    """A dynamic default for `trait` of a parent class: a fresh copy of `value` for each spawner."""
    return default(trait)(lambda self: copy.deepcopy(value))


class CourseSpawner(DockerSpawner):
    """DockerSpawner with the course's places, hardening and messages (module docstring)."""

    data_dir = Unicode(defaults.DATA_DIR, help="""The hub's data folder: each student's disk
        (<data_dir>/disks/<user>.img) is mounted at <data_dir>/users/<user>, whose src is the
        container's ~/catkin_ws/src and whose grades is its ~/grades (read-only).""").tag(config=True)
    disk_limit = Unicode(defaults.DISK_LIMIT, help="""The size of each student's disk (2G, 512M ...,
        at least 8M), its blocks reserved on the host when it is first made: at the limit the
        student's writes fail with `No space left on device`, nothing else notices. A disk made
        already keeps its size.""").tag(config=True)
    home_limit = Unicode(defaults.HOME_LIMIT, help="""The size of the container's home folder and of
        its /tmp, each a tmpfs counted in the memory limit (the image itself is read-only).""").tag(config=True)
    pids_limit = Integer(defaults.PIDS_LIMIT, help="""Processes in one student's container, at most
        (a fork bomb stays theirs).""").tag(config=True)
    userns = Unicode(defaults.USERNS, help="""podman's user namespace mode of each container: `auto`
        maps the student's uid 1000 to a host uid no file of the host's and no other running
        container has.""").tag(config=True)
    student_uid = Integer(defaults.STUDENT_UID, help="""The image's student user: owns the src folder
        on a new disk.""").tag(config=True)

    @validate("disk_limit", "home_limit")
    def _a_size(self, proposal: Dict[str, Any]) -> str:
        try:
            disks.size_bytes(proposal["value"])
        except ValueError as err:
            raise TraitError("CourseSpawner.%s: %s" % (proposal["trait"].name, err)) from None
        return proposal["value"]

    # --- DockerSpawner's and Spawner's traits, with the course's defaults ----------------------

    _image_default = _course_default("image", defaults.IMAGE)
    _pull_policy_default = _course_default("pull_policy", "never")  # no registry: the image is built here
    _cmd_default = _course_default("cmd", list(defaults.SINGLEUSER_COMMAND))
    # the container goes when the server stops; the student's files are on their disk
    _remove_default = _course_default("remove", True)
    _use_internal_ip_default = _course_default("use_internal_ip", True)
    _mem_limit_default = _course_default("mem_limit", defaults.MEM_LIMIT)
    _cpu_limit_default = _course_default("cpu_limit", defaults.CPU_LIMIT)
    _start_timeout_default = _course_default("start_timeout", defaults.START_TIMEOUT_S)
    _http_timeout_default = _course_default("http_timeout", defaults.START_TIMEOUT_S)

    @default("extra_host_config")
    def _extra_host_config_default(self) -> Dict[str, Any]:
        return containers.host_config(self.pids_limit, self.home_limit)

    @default("extra_create_kwargs")
    def _extra_create_kwargs_default(self) -> Dict[str, Any]:
        # docker-py refuses UsernsMode in create_host_config, so it goes into the request's
        # HostConfig directly
        return {"host_config": {"UsernsMode": self.userns}}

    # --- the user's places, from course_hub.names ----------------------------------------------

    def place(self) -> names.Places:
        """Every place of this spawner's user (course_hub.names)."""
        return names.places(self.data_dir, self.user.name)

    @default("object_name")
    def _object_name_default(self) -> str:
        """The container's name (DockerSpawner calls this method by name when the image changes)."""
        return names.container(self.user.name)

    @default("network_name")
    def _network_name_default(self) -> str:
        return self.place().network

    @default("volumes")
    def _volumes_default(self) -> Dict[str, Any]:
        return containers.mounts(self.place())["volumes"]

    @default("read_only_volumes")
    def _read_only_volumes_default(self) -> Dict[str, Any]:
        return containers.mounts(self.place())["read_only_volumes"]

    # --- the spawn ------------------------------------------------------------------------------

    def prepare(self) -> str:
        """Before the container: the data folder's layout, the user's disk mounted and their
        network made; the network's gateway, where the container reaches the hub's API. Blocking:
        `start` runs it in a thread, as DockerSpawner runs its engine calls, so a slow engine or
        disk never stalls the hub's event loop (every other user's page)."""
        place = self.place()
        layout.lay_out(self.data_dir)
        disks.ensure(place, disks.size_bytes(self.disk_limit), self.student_uid)
        return containers.ensure_network(self.client, place)

    async def start(self) -> Tuple[str, int]:
        gateway = await asyncio.get_running_loop().run_in_executor(None, self.prepare)
        self.hub_connect_url = "http://%s:%d" % (gateway, urlparse(self.hub.api_url).port)
        ip, port = await super().start()
        deadline = time.monotonic() + self.start_timeout
        while time.monotonic() < deadline:
            status = await self.poll()
            if status is not None:
                raise RuntimeError(status if isinstance(status, str) else "your server stopped while starting "
                                   "(exit status %s); your files are safe, ask your TA" % status)
            try:
                _, writer = await asyncio.wait_for(asyncio.open_connection(ip, port), CONNECT_TIMEOUT_S)
            except (OSError, asyncio.TimeoutError):
                await asyncio.sleep(LOOK_EVERY_S)
                continue
            writer.close()
            return ip, port
        raise RuntimeError("your server did not start within %d s; your files are safe, ask your TA"
                           % self.start_timeout)

    async def poll(self) -> Optional[Any]:
        status = await super().poll()
        if status is None or status == 0:
            return status
        container = await self.get_object()
        if not container:
            return status
        return containers.exit_reason(container.get("State") or {}, self.mem_limit)

    async def stop(self, now: bool = False) -> None:
        """DockerSpawner's stop (the container removed), then the user's network."""
        await super().stop(now=now)
        await asyncio.get_running_loop().run_in_executor(None, containers.remove_network, self.client, self.place())
