"""Submissions that build the same, built once: course-lint's mutants (`grade --share-builds`).

A catkin devel space runs a package's Python from its source folder: a script listed in
`catkin_install_python` gets a relay in `devel/lib/<package>/` that executes the file in `src/`, a
module of `catkin_python_setup` a shim that points there, and roslaunch reads launch files from
`src/`. So two overlays whose files differ only in such files build to the same devel space, but
for the overlay's own path, which catkin writes into its text files (setup.sh, the CMake config,
pkg-config, relays). course-lint grades dozens of mutants of one reference, most of them a change
to one Python line or one launch file: each is built once per build inputs (`inputs_key`), and the
others get a copy of that build with the path rewritten (`relocate`), as a student's own
catkin_make would have written it.

Never for a class: one student's build output must never become another's, whatever it holds.
A build whose binaries hold its path (a C++ library's RPATH) is not copied: the submission is
built as usual.
"""
from __future__ import annotations

import hashlib
import os
import shutil
import stat
import threading
from typing import Dict, List, Optional, Tuple

# Folders of a package whose files run at build time, whatever they are (dynamic_reconfigure's cfg/).
BUILD_TIME_FOLDERS = ("cfg",)
BUILD_TIME_NAMES = ("setup.py", "CMakeLists.txt", "package.xml")
COPIED = ("devel",)  # what runs need; build/ is CMake's, read only by a build
TOPLEVEL = "CMakeLists.txt"
_CHUNK = 1 << 20


def runs_from_source(relpath: str, head: bytes) -> bool:
    """Whether a file of a workspace's src/ is read only when it runs, never by the build: a Python
    file (by name or by its shebang) or a launch file, outside the build-time folders and names."""
    parts = relpath.split(os.sep)
    if parts[-1] in BUILD_TIME_NAMES or any(p in BUILD_TIME_FOLDERS for p in parts[:-1]):
        return False
    if parts[-1].endswith((".py", ".launch")):
        return True
    return head.startswith(b"#!") and b"python" in head.split(b"\n", 1)[0]


def inputs_key(src: str) -> str:
    """A digest of what a build of the workspace folder `src` reads: every entry's path, kind and
    mode, a link's target, and each file's content except of files that run from source (for those,
    only that they exist, with their mode). Never follows a link."""
    digest = hashlib.sha256()
    for folder, dirs, files in os.walk(src):
        dirs.sort()
        for name in sorted(dirs + files):
            path = os.path.join(folder, name)
            rel = os.path.relpath(path, src)
            info = os.lstat(path)
            digest.update(b"%s\0%o\0" % (rel.encode("utf-8", "surrogateescape"), info.st_mode))
            if stat.S_ISLNK(info.st_mode):
                digest.update(os.readlink(path).encode("utf-8", "surrogateescape") + b"\0")
            elif stat.S_ISREG(info.st_mode):
                with open(path, "rb") as f:
                    head = f.read(256)
                    if runs_from_source(rel, head):
                        continue
                    digest.update(head)
                    for chunk in iter(lambda: f.read(_CHUNK), b""):
                        digest.update(chunk)
                digest.update(b"\0")
    return digest.hexdigest()


def relocate(donor: str, ws: str) -> Optional[str]:
    """Copy `donor`'s devel folder into the workspace `ws` with every mention of
    `donor`'s path in their text files made `ws`'s. Returns None when done, else why it could not
    be (a binary file holding the path: the caller builds `ws` itself); the partial copy is removed."""
    old, new = os.path.abspath(donor).encode(), os.path.abspath(ws).encode()
    for name in COPIED:
        shutil.rmtree(os.path.join(ws, name), ignore_errors=True)
    try:
        for name in COPIED:
            if os.path.isdir(os.path.join(donor, name)):
                shutil.copytree(os.path.join(donor, name), os.path.join(ws, name), symlinks=True)
        top = os.path.join(donor, "src", TOPLEVEL)  # the link catkin_make puts in src/
        if os.path.islink(top) and not os.path.lexists(os.path.join(ws, "src", TOPLEVEL)):
            os.symlink(os.readlink(top), os.path.join(ws, "src", TOPLEVEL))
        for name in COPIED:
            for folder, _dirs, files in os.walk(os.path.join(ws, name)):
                for file in files:
                    why = _rewrite(os.path.join(folder, file), old, new)
                    if why:
                        raise _CannotCopy(why)
    except (OSError, _CannotCopy) as err:
        for name in COPIED:
            shutil.rmtree(os.path.join(ws, name), ignore_errors=True)
        return str(err)
    return None


class _CannotCopy(Exception):
    pass


def _rewrite(path: str, old: bytes, new: bytes) -> str:
    """Replace `old` by `new` in a regular text file (never through a link); "" or why not."""
    if not stat.S_ISREG(os.lstat(path).st_mode):
        return ""  # a link stays as it is
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | getattr(os, "O_CLOEXEC", 0))
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            return ""
        data = f.read()
    if old not in data:
        return ""
    if b"\0" in data:
        return "%s is a binary file holding the build's path" % path
    mode = stat.S_IMODE(os.lstat(path).st_mode)
    with open(path, "wb") as f:
        f.write(data.replace(old, new))
    os.chmod(path, mode)
    return ""


class BuildShare:
    """The builds of one grading by inputs key: the first submission with a key builds, the others
    wait for it and take a copy (thread-safe; every method returns at once or when that build ends)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._builds: Dict[str, Tuple[threading.Event, List[Optional[str]]]] = {}

    def claim(self, key: str, ws: str) -> Tuple[bool, Optional[str]]:
        """(True, None): build `ws` yourself and call done(); (False, donor ws) once the first build
        with this key has ended well; (True, None) again when it failed (build yourself: a build's
        failure is reported from the submission's own build log)."""
        with self._lock:
            entry = self._builds.get(key)
            if entry is None:
                self._builds[key] = (threading.Event(), [None])
                return True, None
        event, donor = entry
        event.wait()
        return (False, donor[0]) if donor[0] else (True, None)

    def done(self, key: str, ws: str, ok: bool) -> None:
        with self._lock:
            event, donor = self._builds[key]
        donor[0] = ws if ok else None
        event.set()
