"""A disk of its own for every student: their folders on a file system the kernel bounds.

A student's `catkin_ws/src` (and the grades the hub copies to them) live on an ext4 file system in
a file of a fixed size, `<data>/disks/<slug>.img`, loop-mounted at `<data>/users/<slug>` before
their server starts. The file's blocks are reserved when it is made (`fallocate`), so what a
student writes can never take space from the host, the hub's database or another student: at the
limit their own writes fail with `No space left on device`, and nothing else notices. The mount
is `nosuid,nodev`: a file the student made set-uid in their container is an ordinary file on the
host.

Made once and kept: a server's stop, a cull or a new image leave the disk as it is. The mount
stays until the machine restarts; the next spawn (or `hub_grade`) mounts it again.
"""
from __future__ import annotations

import os
import re
import subprocess
from typing import List

from course_hub.names import Places

MOUNT_OPTIONS = "loop,nosuid,nodev,noatime"
UNITS = {"": 1, "K": 2 ** 10, "M": 2 ** 20, "G": 2 ** 30, "T": 2 ** 40}
SMALLEST = 8 * 2 ** 20  # ext4 with room for a few files


class DiskError(RuntimeError):
    """A student's disk could not be made or mounted; the message says which and why."""


def size_bytes(text: str) -> int:
    """`2G`, `512M`, `1048576` -> bytes; ValueError for anything else or under 8M."""
    found = re.fullmatch(r"\s*(\d+)\s*([KMGT]?)i?B?\s*", str(text), re.I)
    if not found:
        raise ValueError("%r is no disk size (write it as 2G, 512M ...)" % text)
    size = int(found.group(1)) * UNITS[found.group(2).upper()]
    if size < SMALLEST:
        raise ValueError("a student's disk of %s is too small: at least 8M" % text)
    return size


def _run(command: List[str], what: str) -> None:
    done = subprocess.run(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, check=False)
    if done.returncode != 0:
        raise DiskError("%s: `%s` exited %d: %s" % (what, " ".join(command), done.returncode, done.stdout.strip()))


def make_image(path: str, size: int) -> None:
    """An ext4 file system of `size` bytes in the file `path`, its blocks reserved."""
    os.makedirs(os.path.dirname(path), mode=0o700, exist_ok=True)
    partial = path + ".new"
    with open(partial, "wb") as image:
        try:
            os.posix_fallocate(image.fileno(), 0, size)
        except OSError as err:
            os.unlink(partial)
            raise DiskError("cannot reserve %d MiB for %s: %s" % (size // 2 ** 20, path, err.strerror)) from None
    os.chmod(partial, 0o600)
    # -m 0: no blocks kept back for root (nothing runs as root on it); nodiscard: mkfs would punch
    # holes in the reserved file (it discards a device's blocks); no lazy init: the file's
    # blocks are reserved already, so writing its tables now costs nothing later
    _run(["mkfs.ext4", "-q", "-F", "-m", "0", "-E", "lazy_itable_init=0,lazy_journal_init=0,nodiscard", partial],
         "making the file system of %s" % path)
    os.rename(partial, path)


def mount(image: str, target: str) -> None:
    os.makedirs(target, mode=0o755, exist_ok=True)
    if os.listdir(target):
        raise DiskError("%s holds files already and is no mount point: move them onto the student's disk "
                        "(%s) by hand before their server starts" % (target, image))
    _run(["mount", "-o", MOUNT_OPTIONS, image, target], "mounting %s" % image)


def ensure(places: Places, size: int, uid: int) -> Places:
    """`places.home` mounted from the user's disk image (made now if missing), with `src` (theirs,
    uid `uid`) and `grades` (root's, readable) on it. DiskError when that cannot be done."""
    if not os.path.exists(places.disk_image):
        make_image(places.disk_image, size)
    if not os.path.ismount(places.home):
        mount(places.disk_image, places.home)
    os.chmod(places.home, 0o755)
    lost = os.path.join(places.home, "lost+found")
    if os.path.isdir(lost):
        os.chmod(lost, 0o700)
    if not os.path.isdir(places.src):
        os.mkdir(places.src)
        os.chown(places.src, uid, uid)
        os.chmod(places.src, 0o755)
    os.makedirs(places.grades, exist_ok=True)
    os.chmod(places.grades, 0o755)
    return places


def unmount(places: Places) -> None:
    """Unmount the user's disk (the hub's tests; a student's server must be stopped first)."""
    if os.path.ismount(places.home):
        _run(["umount", places.home], "unmounting %s" % places.home)
