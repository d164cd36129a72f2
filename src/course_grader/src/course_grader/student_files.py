"""Reading what a student's code wrote (a run's ROS logs, a build's folder) from the trusted side.

A run's logs (ROS's logs in the student's run home) are copied into the grader's outputs; a
build folder is read to judge the build. The folder is the student's: its code may have left links to the grader's files, pipes, deep
trees or huge files there, and where no PID namespace ends every student process with the run
(isolation `user only`) a leftover may still change it while it is copied. So the trusted side
walks it by directory descriptor without following a link, copies regular files alone, each
opened without following a link, and keeps at most MAX_FILES files and the last MAX_FILE_BYTES
of each. A copy is only ever shown as a log: no verdict is read from it.
"""
from __future__ import annotations

import os
import stat
from typing import Callable, Iterator, List, Optional, Tuple

MAX_FILES = 200
MAX_FILE_BYTES = 256 * 1024


def read_tree(source: str, wanted: Callable[[str], bool] = lambda path: True, max_files: int = MAX_FILES,
              max_bytes: int = MAX_FILE_BYTES) -> Iterator[Tuple[str, bytes]]:
    """(relative path, last `max_bytes` of the content) of at most `max_files` regular files
    under `source` (the student's) whose relative path is `wanted`, in a stable order; never
    through a link, whether a file's or a folder's."""
    if not os.path.isdir(source) or os.path.islink(source):
        return
    count = 0
    for folder, dirs, files, folder_fd in os.fwalk(source, follow_symlinks=False):
        dirs.sort()
        relative = os.path.relpath(folder, source)
        for name in sorted(files):
            path = os.path.normpath(os.path.join(relative, name))
            if not wanted(path):
                continue
            if count >= max_files:
                return
            data = _tail(name, folder_fd, max_bytes)
            if data is not None:
                count += 1
                yield path, data


def copy_logs(source: str, target: str, max_files: int = MAX_FILES, max_bytes: int = MAX_FILE_BYTES) -> List[str]:
    """Copy the regular files under `source` (the student's) to the same places under `target`
    (the grader's, created here), each cut to its last `max_bytes`; the relative paths copied."""
    copied: List[str] = []
    for path, data in read_tree(source, max_files=max_files, max_bytes=max_bytes):
        destination = os.path.join(target, path)
        os.makedirs(os.path.dirname(destination), exist_ok=True)
        with open(destination, "wb") as out:
            out.write(data)
        copied.append(path)
    return copied


def read_file(root: str, relative: str, max_bytes: int = MAX_FILE_BYTES) -> Optional[bytes]:
    """The last `max_bytes` of the regular file at `relative` under `root` (the student's), each
    folder on the way opened on its parent's descriptor without following a link; None for a
    link, a pipe, a device, a path with `..`, or nothing there."""
    parts = [p for p in relative.split("/") if p and p != "."]
    if not parts or ".." in parts:
        return None
    try:
        fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError:
        return None
    try:
        for part in parts[:-1]:
            inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)
            os.close(fd)
            fd = inner
        return _tail(parts[-1], fd, max_bytes)
    except OSError:
        return None
    finally:
        os.close(fd)


def _tail(name: str, folder_fd: int, max_bytes: int) -> Optional[bytes]:
    """The last `max_bytes` of the regular file `name` in the folder open as `folder_fd`, with a
    line saying what was left out; None for anything else (a link, a pipe, a device, gone)."""
    try:
        fd = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK, dir_fd=folder_fd)
    except OSError:
        return None
    with os.fdopen(fd, "rb") as f:
        info = os.fstat(f.fileno())
        if not stat.S_ISREG(info.st_mode):
            return None
        if info.st_size <= max_bytes:
            return f.read(max_bytes)
        f.seek(info.st_size - max_bytes)
        return b"[... first %d bytes left out ...]\n" % (info.st_size - max_bytes) + f.read(max_bytes)
