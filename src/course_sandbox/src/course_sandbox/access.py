"""What the sandbox user may reach on the host's filesystem: bubblewrap runs as that user, so a
folder it binds must be reachable (a course behind a 0700 home is not), and a hidden path it
cannot reach needs no hiding."""
from __future__ import annotations

import os
import pwd
import stat
from typing import Callable, Set, Tuple

from course_sandbox import levels


def identity(level: str, user: str) -> Tuple[int, Set[int]]:
    """The uid and groups student code runs with at `level` (setpriv --clear-groups keeps only
    the user's own group)."""
    if levels.switches_user(level):
        entry = pwd.getpwnam(user)
        return entry.pw_uid, {entry.pw_gid}
    return os.getuid(), set(os.getgroups()) | {os.getgid()}


def traverser(uid: int, groups: Set[int]) -> Callable[[str], bool]:
    """Whether `uid` (in `groups`) may pass through a folder, by its mode bits (as the kernel
    decides for a user without capabilities; ACLs are not read)."""
    def can_traverse(path: str) -> bool:
        try:
            info = os.stat(path)
        except OSError:
            return False
        if not stat.S_ISDIR(info.st_mode):
            return False
        if info.st_uid == uid:
            return bool(info.st_mode & stat.S_IXUSR)
        if info.st_gid in groups:
            return bool(info.st_mode & stat.S_IXGRP)
        return bool(info.st_mode & stat.S_IXOTH)
    return can_traverse


def unreachable_part(path: str, can_traverse: Callable[[str], bool]) -> str:
    """The first folder on the way to `path` (itself included) the user cannot pass, or ""."""
    parts = [p for p in os.path.realpath(path).split(os.sep) if p]
    for i in range(len(parts)):
        folder = "/" + "/".join(parts[:i + 1])
        if not can_traverse(folder):
            return folder
    return ""
