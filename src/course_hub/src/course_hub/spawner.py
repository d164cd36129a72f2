"""The course's spawner: DockerSpawner, saying in words why a student's server stopped.

DockerSpawner's poll reports a stopped container as `ExitCode=137, Error='', FinishedAt=...`, and
JupyterHub shows that string to the student whose server failed to start. This one says what
happened (course_hub.hubconfig.exit_reason): out of memory under the course's limit, or the start-up's own exit
code. The container must still be there to be asked, so it is not removed by the engine when it
exits (`auto_remove` off, course_hub.hubconfig); DockerSpawner removes it when the server stops.
"""
from __future__ import annotations

from typing import Any, Optional

from dockerspawner import DockerSpawner

from course_hub.hubconfig import exit_reason


class CourseSpawner(DockerSpawner):
    async def poll(self) -> Optional[Any]:
        status = await super().poll()
        if status is None or status == 0:
            return status
        container = await self.get_object()
        if not container:
            return status
        return exit_reason(container.get("State") or {}, self.mem_limit)
