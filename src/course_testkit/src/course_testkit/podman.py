"""This machine's podman, for the end-to-end suites of the course image, the hub and the arm64
image (tests/e2e): Debian's podman as root (this machine's podman needs runc, cgroupfs and no
default ulimits), the base image, the course image's build, a fresh container of an image, and
each step's wall time.

No image registry is reachable here, so `debian:bookworm` is imported once from a debootstrap
(minbase, the host's Debian mirror) and reused. Where podman cannot run (not root, podman missing
and not installable), `Unavailable` says why: there is no stand-in.

The host's CA bundle is lent to the containers read-only, with a pip.conf pointing at it, so that
pip reaches PyPI through this machine's TLS-intercepting proxy as the host's pip does; apt uses
plain http and needs nothing. Neither goes into an image.

Plain Python and the standard library: Debian's python3 runs it without ROS sourced.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Callable, List, Optional, Sequence, Tuple

CHECKOUT = Path(__file__).resolve().parents[4]  # <checkout>/src/course_testkit/src/course_testkit/podman.py
PODMAN = ["podman", "--runtime", "runc", "--cgroup-manager=cgroupfs"]
BASE_IMAGE = "debian:bookworm"
# The images' tags: $COURSE_IMAGE and $INSTRUCTOR_IMAGE name others (a second checkout's, say).
COURSE_IMAGE = os.environ.get("COURSE_IMAGE") or "localhost/ros-course"  # the student image (the default target)
INSTRUCTOR_IMAGE = os.environ.get("INSTRUCTOR_IMAGE") or "localhost/ros-course-instructor"  # with the answers
CONTAINERS_CONF = Path("/etc/containers/containers.conf")
HOST_CA = Path("/etc/ssl/certs/ca-certificates.crt")
CA_IN_CONTAINER = "/etc/ssl/certs/host-ca-bundle.crt"
PACKAGES = ("podman", "runc", "debootstrap")
DOCKERFILE = CHECKOUT / "docker" / "Dockerfile"


class Unavailable(Exception):
    """podman cannot run here: the reason, for the user."""


class Steps:
    """Each step's wall time, printed as a table at the end."""

    def __init__(self) -> None:
        self.times: List[Tuple[str, float]] = []

    def run(self, name: str, fn, *args, **kwargs):
        print("== %s" % name, flush=True)
        started = time.monotonic()
        result = fn(*args, **kwargs)
        self.times.append((name, time.monotonic() - started))
        print("== %s: %.1f s" % (name, self.times[-1][1]), flush=True)
        return result

    def table(self) -> str:
        return "\n".join(["| step | wall time |", "| --- | --- |"]
                         + ["| %s | %.1f s |" % (name, seconds) for name, seconds in self.times])


def podman(*args: str, check: bool = True, log: Optional[Path] = None, **kwargs) -> subprocess.CompletedProcess:
    """podman with this machine's settings; its output streamed to `log` (or ours)."""
    command = PODMAN + list(args)
    if log is None:
        return subprocess.run(command, check=check, **kwargs)
    with open(log, "ab") as out:
        return subprocess.run(command, check=check, stdout=out, stderr=subprocess.STDOUT, **kwargs)


def ensure_podman() -> None:
    """podman, runc and debootstrap installed, and containers.conf without default ulimits."""
    if os.geteuid() != 0:
        raise Unavailable("podman here runs as root only (rootless podman has no user namespaces to map "
                          "on this machine): run it with sudo")
    missing = [p for p in PACKAGES if shutil.which(p) is None and shutil.which(p, path="/usr/sbin:/sbin") is None]
    if missing:
        print("installing %s" % " ".join(missing), flush=True)
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        if subprocess.run(["apt-get", "update", "-qq"], env=env).returncode != 0 or subprocess.run(
                ["apt-get", "install", "-y", "-qq"] + missing, env=env).returncode != 0:
            raise Unavailable("could not install %s with apt-get" % " ".join(missing))
    text = CONTAINERS_CONF.read_text() if CONTAINERS_CONF.exists() else ""
    wanted = without_default_ulimits(text)
    if wanted != text:
        CONTAINERS_CONF.parent.mkdir(parents=True, exist_ok=True)
        CONTAINERS_CONF.write_text(wanted)
    if podman("info", check=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode != 0:
        raise Unavailable("`podman info` fails here: %s" % podman("info", check=False, stdout=subprocess.PIPE,
                                                                   stderr=subprocess.STDOUT, text=True).stdout[-500:])


def without_default_ulimits(conf: str) -> str:
    """containers.conf text with `default_ulimits = []` in its [containers] table (podman's default
    nofile limit cannot be set in this sandbox: the containers keep the host's)."""
    if re.search(r"^\s*default_ulimits\s*=\s*\[\s*\]", conf, re.MULTILINE):
        return conf
    if re.search(r"^\[containers\][ \t]*$", conf, re.MULTILINE):
        return re.sub(r"^\[containers\][ \t]*$", "[containers]\ndefault_ulimits = []", conf, count=1, flags=re.MULTILINE)
    return conf + ("\n" if conf and not conf.endswith("\n") else "") + "[containers]\ndefault_ulimits = []\n"


def container_name(what: str) -> str:
    """A container's name of this run's own: two checks at once (two checkouts) never remove each
    other's containers."""
    return "ros-course-%s-%d" % (what, os.getpid())


def remove_container(name: str) -> None:
    """Remove the container `name` if there is one (left by an interrupted check, or done with)."""
    podman("rm", "-f", name, check=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def image_exists(name: str) -> bool:
    return podman("image", "exists", name, check=False).returncode == 0


def host_mirror() -> str:
    sources = Path("/etc/apt/sources.list.d/debian.sources")
    if sources.exists():
        m = re.search(r"^URIs:\s*(\S+)", sources.read_text(), re.MULTILINE)
        if m:
            return m.group(1)
    return "http://deb.debian.org/debian"


def import_base(log: Path) -> None:
    """debian:bookworm from a minbase debootstrap, imported once (skipped when present)."""
    if image_exists(BASE_IMAGE):
        print("%s already imported" % BASE_IMAGE, flush=True)
        return
    folder = Path(tempfile.mkdtemp(prefix="bookworm-", dir="/var/tmp"))
    try:
        with open(log, "ab") as out:
            subprocess.run(["debootstrap", "--variant=minbase", "bookworm", str(folder), host_mirror()],
                           check=True, stdout=out, stderr=subprocess.STDOUT)
        tar = subprocess.Popen(["tar", "-C", str(folder), "-c", "."], stdout=subprocess.PIPE)
        podman("import", "-", BASE_IMAGE, stdin=tar.stdout, log=log)
        if tar.wait() != 0:
            raise subprocess.CalledProcessError(tar.returncode, "tar")
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def network_mounts(scratch: Path) -> List[str]:
    """-v options lending the host's CA bundle and a pip.conf that uses it (see the docstring)."""
    if not HOST_CA.exists():
        return []
    pip_conf = scratch / "pip.conf"
    pip_conf.write_text("[global]\ncert = %s\n" % CA_IN_CONTAINER)
    return ["-v", "%s:%s:ro" % (HOST_CA, CA_IN_CONTAINER), "-v", "%s:/etc/pip.conf:ro" % pip_conf]


def build_course_image(scratch: Path, log: Path) -> None:
    """Both images of docker/Dockerfile: the instructor's (a target), then the student's (the default)."""
    for target in ("instructor", None):
        podman("build", "--network", "host", *network_mounts(scratch), "-f", str(DOCKERFILE),
               *(["--target", target] if target else []), "-t", INSTRUCTOR_IMAGE if target else COURSE_IMAGE,
               str(CHECKOUT), log=log)


def run_in_image(image: str, command: Sequence[str], log: Path, extra: Sequence[str] = ()) -> int:
    """A fresh container of `image` (its own loopback-only network), removed afterwards; its exit code."""
    return podman("run", "--rm", "--network", "none", "--shm-size", "1g", *extra, image, *command,
                  check=False, log=log).returncode


def last_line(path: Path, pattern: str) -> str:
    lines = [line for line in path.read_text(errors="replace").splitlines() if re.search(pattern, line)]
    return lines[-1].strip() if lines else "(no such line)"


def image_uid(image: str) -> int:
    """The uid the image's user has (the volume is handed to it, as a student's own folder is theirs)."""
    return int(podman("run", "--rm", "--network", "none", "--entrypoint", "id", image, "-u",
                      stdout=subprocess.PIPE, text=True).stdout.strip())


def run_steps(name: str, action: Callable[[Steps, Path], bool], logs: Path) -> int:
    """`action(steps, scratch)` with podman ready, a scratch folder removed afterwards, and each
    step's time printed at the end, then `<name>: ok` or `FAILED`; the exit code (2: podman cannot
    run here, and why on stderr)."""
    logs.mkdir(parents=True, exist_ok=True)
    steps = Steps()
    scratch = Path(tempfile.mkdtemp(prefix="%s-" % name.replace(" ", "-")))
    scratch.chmod(0o755)
    try:
        ensure_podman()
        ok = action(steps, scratch)
    except Unavailable as e:
        print("%s: %s" % (name, e), file=sys.stderr)
        return 2
    except subprocess.CalledProcessError as e:
        print("%s: %s failed (exit %s); see the logs in %s" % (name, " ".join(map(str, e.cmd))[:200],
                                                               e.returncode, logs), file=sys.stderr)
        ok = False
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    print(steps.table())
    print("%s: %s (logs in %s)" % (name, "ok" if ok else "FAILED", logs))
    return 0 if ok else 1


def require_ok(name: str, code: int) -> None:
    """An end-to-end test's verdict on run_steps' exit code: nothing when 0, else pytest's failure,
    without a traceback (the lines printed above say which step failed, or why podman cannot run)."""
    import pytest  # a test's: the tools that run steps need none
    if code == 2:
        pytest.fail("%s cannot run here: the reason is printed above" % name, pytrace=False)
    if code != 0:
        pytest.fail("%s failed: the lines above say which step" % name, pytrace=False)
