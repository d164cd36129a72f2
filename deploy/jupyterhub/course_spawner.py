"""The course's spawner: DockerSpawner, saying in words why a student's server stopped.

It lives beside the hub's config, not in a catkin package: it runs in the hub's own venv
(.venv-hub, requirements-hub.txt), where dockerspawner is; the config puts this folder and
course_hub's on the hub's path.

DockerSpawner's poll reports a stopped container as `ExitCode=137, Error='', FinishedAt=...`, and
JupyterHub shows that string to the student whose server failed to start. This one says what
happened (course_hub.hubconfig.exit_reason): out of memory under the course's limit, or the
start-up's own exit code. The container must still be there to be asked, so it is not removed
by the engine when it exits (`auto_remove` off, course_hub.hubconfig); DockerSpawner removes it
when the server stops.

Its container is named by course_hub.names, like the user's network and folders (the hooks of
course_hub.hubconfig set those).

It also waits, in `start`, until the server accepts connections on its port or its container
stops: a server that dies while starting fails the spawn with that sentence, which the student
reads on the spawn page (JupyterHub's own wait for the server's HTTP answer was seen taking a
server killed by its memory limit for a running one).
"""
from __future__ import annotations

import asyncio
import time
from typing import Any, Optional, Tuple

from dockerspawner import DockerSpawner
from traitlets import default

from course_hub import names
from course_hub.hubconfig import exit_reason

CONNECT_TIMEOUT_S = 2.0
LOOK_EVERY_S = 0.5


class CourseSpawner(DockerSpawner):
    @default("object_name")
    def _object_name_default(self) -> str:
        """The container's name from course_hub.names, as every other place of the user is named
        (DockerSpawner's own template would escape the name its own way)."""
        return names.container(self.user.name)

    async def poll(self) -> Optional[Any]:
        status = await super().poll()
        if status is None or status == 0:
            return status
        container = await self.get_object()
        if not container:
            return status
        return exit_reason(container.get("State") or {}, self.mem_limit)

    async def start(self) -> Tuple[str, int]:
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
