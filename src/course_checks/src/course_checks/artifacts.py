"""Where a milestone check leaves what a grader shows the student: each student process's output
(`<name>.log`) and pictures such as the turtlesim canvas (`<name>.png`).

The grader sets COURSE_ARTIFACTS_DIR to a folder per submission and milestone and reads it after
the run; without it (a plain `rostest`), a fresh temporary folder is used.
"""
from __future__ import annotations

import os
import stat
import tempfile
from typing import Optional

ENV_VAR = "COURSE_ARTIFACTS_DIR"
_fallback: Optional[str] = None


def artifact_dir() -> str:
    """The folder for this run's artifacts (created if needed)."""
    global _fallback
    path = os.environ.get(ENV_VAR)
    if not path:
        if _fallback is None:
            _fallback = tempfile.mkdtemp(prefix="milestone-")
        path = _fallback
    os.makedirs(path, exist_ok=True)
    return path


def artifact_path(name: str, suffix: str = ".log") -> str:
    """A path `<artifact_dir>/<name><suffix>` not used yet in this run (`name-2`, `name-3`, ...)."""
    base = os.path.join(artifact_dir(), name.replace("/", "_"))
    path, n = base + suffix, 1
    while os.path.exists(path):
        n += 1
        path = "%s-%d%s" % (base, n, suffix)
    return path


# What a canvas snapshot may be: turtlesim's PNGs are ~10-100 kB.
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
MAX_CANVAS_BYTES = 8 * 1024 * 1024


class UnsafeFile(ValueError):
    """A file the check refuses to copy into the student's outputs (and why)."""


def open_without_links(path: str) -> int:
    """A read-only descriptor of the file at the absolute `path`, opened one component at a time
    from / with O_NOFOLLOW: no symbolic link anywhere on the way (a folder swapped for a link
    between a check and the open cannot redirect it, as it could with realpath then open), no
    `.` or `..`. O_NONBLOCK: a FIFO does not hang the open. Raises UnsafeFile or OSError."""
    if not os.path.isabs(path):
        raise UnsafeFile("%r is not an absolute path" % path)
    parts = [p for p in path.split("/") if p]
    if not parts or any(p in (".", "..") for p in parts):
        raise UnsafeFile("%r names no file plainly" % path)
    fd = os.open("/", os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        for part in parts[:-1]:
            inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)
            os.close(fd)
            fd = inner
        return os.open(parts[-1], os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC, dir_fd=fd)
    finally:
        os.close(fd)


def read_png(path: str, limit: int = MAX_CANVAS_BYTES) -> bytes:
    """The bytes of the PNG at `path`, if it is a regular file reached without links, at most
    `limit` bytes, starting with the PNG signature; else UnsafeFile (or OSError). A check runs as
    root outside the student's sandbox: the path comes from a service, and nothing but a picture
    may come out of it."""
    fd = open_without_links(path)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise UnsafeFile("%s is not a regular file" % path)
        if info.st_size > limit:
            raise UnsafeFile("%s has %d bytes, more than %d" % (path, info.st_size, limit))
        with os.fdopen(os.dup(fd), "rb") as f:
            if f.read(len(PNG_SIGNATURE)) != PNG_SIGNATURE:
                raise UnsafeFile("%s is not a PNG" % path)
            rest = f.read(limit + 1 - len(PNG_SIGNATURE))  # st_size may lie (/proc) or grow meanwhile
        if len(rest) + len(PNG_SIGNATURE) > limit:
            raise UnsafeFile("%s is larger than %d bytes" % (path, limit))
        return PNG_SIGNATURE + rest
    finally:
        os.close(fd)


def save_canvas(service: str = "/turtlesim/snapshot", name: str = "canvas") -> Optional[str]:
    """Ask turtlesim (our node's `~snapshot` Trigger service) for its canvas and copy the PNG to
    `<artifact_dir>/<name>.png`. The path, or None when there is no such service or its answer
    is not a safe PNG (read_png): a picture helps the grader and is never part of a verdict.

    Who answers matters as much as what: in a milestone check that installed
    course_milestones.guard, this ServiceProxy call reaches only the simulator recorded before
    the student's code ran (a student's service under this name is refused, and named in the
    verdict). Without a guard (the student's own launch file started the simulator), read_png is
    what keeps the copy to a picture."""
    import rospy
    from std_srvs.srv import Trigger
    try:
        rospy.wait_for_service(service, 2.0)
        reply = rospy.ServiceProxy(service, Trigger)()
    except Exception:  # noqa: BLE001 - no snapshot service, it died, or the guard refused it: no picture
        return None
    if not reply.success:
        return None
    try:
        data = read_png(reply.message)
    except (UnsafeFile, OSError, ValueError):  # ValueError: a NUL in the path
        return None
    path = artifact_path(name, ".png")
    with open(path, "xb") as out:
        out.write(data)
    return path
