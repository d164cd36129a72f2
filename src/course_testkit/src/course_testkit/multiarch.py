"""The course image for linux/amd64 and linux/arm64 (Apple Silicon Macs, ARM laptops), both built
on this amd64 machine by podman from the one docker/Dockerfile, and joined in one manifest list:
what `make image-multiarch` (tools/multiarch.py) and the arm64 image's end-to-end suite
(tests/e2e/test_arm64.py, `make image-arm64-check`) share.

A foreign architecture runs under Debian's qemu-user-static, registered with the kernel's
binfmt_misc (mounted here first when it is not) with the F flag: the kernel opens the emulator
once, at registration, so processes in a container find it without a copy in the image. The arm64
root file system is a minbase debootstrap for that architecture (its second stage runs under the
emulator), imported as course_testkit.podman imports the amd64 `debian:bookworm`, under a name of
its own; the Dockerfile's `BASE_IMAGE` argument names it. Everything else is the same file and
the same install.sh for both. See docs/images.md.
"""
from __future__ import annotations

import json
import os
import platform
import re
import shutil
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Dict, List, Sequence, Tuple

from course_testkit import podman as podman_host
from course_testkit.podman import CHECKOUT, DOCKERFILE, Unavailable, podman
from course_checks.waiting import wait_for
from course_testkit.workbench import Workbench, WorkbenchError

ARCHES = ("amd64", "arm64")  # the platforms the manifest list carries (linux/<arch>)
# uname's machine name -> the OCI/Debian architecture name
MACHINES = {"x86_64": "amd64", "amd64": "amd64", "aarch64": "arm64", "arm64": "arm64"}
# OCI architecture -> qemu's name for it (its binfmt_misc entry is qemu-<name>)
QEMU_NAMES = {"amd64": "x86_64", "arm64": "aarch64"}
IMAGE_PREFIX = "localhost/ros-course"
MANIFEST = "localhost/ros-course-multiarch"
BINFMT = Path("/proc/sys/fs/binfmt_misc")
EMULATION_PACKAGES = ("qemu-user-static", "binfmt-support")
BUILD_TIMES = "build-times.json"  # in the logs folder: each architecture's last build time, for `figures`
LOGS = CHECKOUT / "podman-logs" / "multiarch"  # each step's log, by default
# The correct chatter package the self-check grades (a graded sample of the test suite).
CHATTER_SAMPLE = CHECKOUT / "courses" / "robotics_labs" / "samples" / "lab2_chatter_scripts"
# Under emulation a process runs several times slower: the checks wait this much longer.
START_TIMEOUT_S = 600.0
SELF_CHECK_TIMEOUT_S = 1800.0
DESKTOP_TIMEOUT_S = 300.0  # the desktop's X session and VNC server start on its first websocket


def oci_arch(machine: str) -> str:
    """The OCI architecture of uname's machine name ('x86_64' -> 'amd64'); ValueError otherwise."""
    try:
        return MACHINES[machine.lower()]
    except KeyError:
        raise ValueError("no course image for the machine %r (only %s)" % (machine, ", ".join(ARCHES))) from None


def host_arch() -> str:
    return oci_arch(platform.machine())


def image_name(arch: str) -> str:
    """Each architecture's image, under a tag of its own: localhost/ros-course-arm64."""
    if arch not in ARCHES:
        raise ValueError("unknown architecture %r (only %s)" % (arch, ", ".join(ARCHES)))
    return "%s-%s" % (IMAGE_PREFIX, arch)


def base_image(arch: str, host: str) -> str:
    """The Debian 12 base for `arch`: the host's own is course_testkit.podman's `debian:bookworm`; a foreign
    one is imported as `localhost/debian:bookworm-<arch>` (a name podman never resolves to the host's)."""
    if arch == host:
        return podman_host.BASE_IMAGE
    return "localhost/debian:bookworm-%s" % arch


def binfmt_entry(arch: str) -> str:
    return "qemu-%s" % QEMU_NAMES[arch]


def binfmt_usable(status: str) -> bool:
    """Whether a /proc/sys/fs/binfmt_misc/qemu-* file's text is an entry a container can use:
    enabled, and with the F flag (the emulator opened at registration, not looked up in the image)."""
    flags = re.search(r"^flags:\s*(\S*)", status, re.MULTILINE)
    return status.startswith("enabled") and flags is not None and "F" in flags.group(1)


def manifest_platforms(inspect: Dict) -> List[str]:
    """The `os/architecture` of each image a manifest list (`podman manifest inspect`'s JSON) holds."""
    return sorted("%s/%s" % (m.get("platform", {}).get("os", "?"), m.get("platform", {}).get("architecture", "?"))
                  for m in inspect.get("manifests") or [])


def ensure_emulation(arch: str) -> None:
    """qemu-user-static and binfmt-support installed, binfmt_misc mounted, the entry for `arch`
    enabled with the F flag: then the kernel runs `arch`'s programs, in containers too."""
    if arch == host_arch():
        return
    missing = [p for p in EMULATION_PACKAGES if subprocess.run(
        ["dpkg-query", "-W", "-f=${Status}", p], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
        text=True).stdout != "install ok installed"]
    if missing:
        print("installing %s" % " ".join(missing), flush=True)
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        if subprocess.run(["apt-get", "update", "-qq"], env=env).returncode != 0 or subprocess.run(
                ["apt-get", "install", "-y", "-qq", "--no-install-recommends"] + missing, env=env).returncode != 0:
            raise Unavailable("could not install %s with apt-get" % " ".join(missing))
    if not (BINFMT / "register").exists():
        done = subprocess.run(["mount", "-t", "binfmt_misc", "binfmt_misc", str(BINFMT)],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if done.returncode != 0:
            raise Unavailable("cannot mount binfmt_misc on %s: %s" % (BINFMT, done.stdout.strip()))
    entry = BINFMT / binfmt_entry(arch)
    if not entry.exists() or not binfmt_usable(entry.read_text()):
        # binfmt-support's registration of qemu-user-static's entry (/usr/share/binfmts/qemu-*)
        subprocess.run(["update-binfmts", "--enable", binfmt_entry(arch)], check=False)
    if not entry.exists() or not binfmt_usable(entry.read_text()):
        raise Unavailable("%s is not registered with the F flag: %s" % (
            entry, entry.read_text().strip() if entry.exists() else "missing"))


def probe_emulation(arch: str) -> None:
    """A container of `arch`'s base image runs, and its kernel machine is `arch`'s (qemu's)."""
    probe = podman("run", "--rm", "--network", "none", "--arch", arch, base_image(arch, host_arch()),
                   "uname", "-m", check=False, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if probe.stdout.strip() != QEMU_NAMES[arch]:
        raise Unavailable("a linux/%s container does not run here: %s" % (arch, probe.stdout.strip()[-300:]))
    print("a linux/%s container runs here: uname -m says %s" % (arch, probe.stdout.strip()), flush=True)


def import_foreign_base(arch: str, log: Path) -> None:
    """`arch`'s Debian 12 from a minbase debootstrap (its second stage under qemu), imported with
    its architecture recorded; skipped when present."""
    name = base_image(arch, host_arch())
    if podman_host.image_exists(name):
        print("%s already imported" % name, flush=True)
        return
    folder = Path(tempfile.mkdtemp(prefix="bookworm-%s-" % arch, dir="/var/tmp"))
    try:
        with open(log, "ab") as out:
            subprocess.run(["debootstrap", "--arch=%s" % arch, "--variant=minbase", "bookworm", str(folder),
                            podman_host.host_mirror()], check=True, stdout=out, stderr=subprocess.STDOUT)
        tar = subprocess.Popen(["tar", "-C", str(folder), "-c", "."], stdout=subprocess.PIPE)
        podman("import", "--os", "linux", "--arch", arch, "-", name, stdin=tar.stdout, log=log)
        if tar.wait() != 0:
            raise subprocess.CalledProcessError(tar.returncode, "tar")
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def import_base(arch: str, log: Path) -> None:
    if arch == host_arch():
        podman_host.import_base(log)
    else:
        import_foreign_base(arch, log)


def build_image(arch: str, scratch: Path, log: Path) -> None:
    """docker/Dockerfile's student image (its default target) for linux/<arch>."""
    podman("build", "--network", "host", *podman_host.network_mounts(scratch), "--platform", "linux/%s" % arch,
           "--build-arg", "BASE_IMAGE=%s" % base_image(arch, host_arch()), "-f", str(DOCKERFILE),
           "-t", image_name(arch), str(CHECKOUT), log=log)


def make_manifest(arches: Sequence[str], log: Path) -> List[str]:
    """The manifest list MANIFEST, made anew from the images of `arches`; the platforms it holds."""
    if podman("manifest", "exists", MANIFEST, check=False).returncode == 0:
        podman("manifest", "rm", MANIFEST, log=log)
    podman("manifest", "create", MANIFEST, log=log)
    for arch in arches:
        podman("manifest", "add", MANIFEST, "containers-storage:%s" % image_name(arch), log=log)
    inspect = podman("manifest", "inspect", MANIFEST, stdout=subprocess.PIPE, text=True).stdout
    return manifest_platforms(json.loads(inspect))


def image_exists_or_fail(arch: str) -> str:
    name = image_name(arch)
    if not podman_host.image_exists(name):
        raise Unavailable("%s is not built: run make image-multiarch first" % name)
    return name


def run_demo(arch: str, log: Path) -> Tuple[int, float, str]:
    """The image's CMD (make demo) in a fresh container: (exit code, wall seconds, its summary line)."""
    name = image_exists_or_fail(arch)
    started = time.monotonic()
    code = podman_host.run_in_image(name, [], log)
    seconds = time.monotonic() - started
    return code, seconds, podman_host.last_line(log, r"^demo: |turtles|\.png")


def image_user_ids(name: str) -> Tuple[int, int]:
    """The uid and gid of the image's user (student), which must own the mounted workspace."""
    out = podman("run", "--rm", "--network", "none", name, "id", "-u", stdout=subprocess.PIPE, text=True).stdout
    gid = podman("run", "--rm", "--network", "none", name, "id", "-g", stdout=subprocess.PIPE, text=True).stdout
    return int(out.strip()), int(gid.strip())


class ContainerWorkbench(Workbench):
    """`make jupyter` in a container of `image`, its port published on the host's loopback, the
    student's src/ mounted from `src`: course_testkit's REST and terminal client drives it as it
    drives a workbench on the host."""

    def __init__(self, image: str, src: Path, log: Path) -> None:
        super().__init__(env={}, home=str(src.parent))  # the caller's scratch folder, removed by it
        self.image, self.src, self.log = image, src, log
        self.container = "ros-course-multiarch-workbench"

    def start(self) -> "ContainerWorkbench":
        podman_host.remove_container(self.container)
        began = time.monotonic()
        podman("run", "-d", "--name", self.container, "--shm-size", "1g", "-p", "127.0.0.1:%d:8888" % self.port,
               "-e", "JUPYTER_TOKEN=%s" % self.token, "-v", "%s:/home/student/catkin_ws/src" % self.src,
               self.image, "make", "jupyter", log=self.log)
        answered = wait_for(lambda: self.status("/api/status") == 200 or not self.running(), START_TIMEOUT_S, 0.5)
        if not answered or not self.running():
            self.stop()
            raise WorkbenchError("make jupyter in %s did not answer within %.0f s; see %s"
                                 % (self.image, START_TIMEOUT_S, self.log))
        self.started_s = time.monotonic() - began
        return self

    def running(self) -> bool:
        state = podman("inspect", "--format", "{{.State.Running}}", self.container, check=False,
                       stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.strip()
        return state == "true"

    def stop(self) -> None:
        podman("logs", self.container, check=False, log=self.log)
        podman_host.remove_container(self.container)


def workbench_and_self_check(arch: str, scratch: Path, log: Path) -> List[Tuple[str, bool, str]]:
    """make jupyter's workbench over HTTP, its desktop's VNC server through the websocket, then
    course-check typed in one of its terminals on a correct chatter package: a (check, passed,
    what was seen) for each."""
    name = image_exists_or_fail(arch)
    src = scratch / "src"
    shutil.copytree(CHATTER_SAMPLE, src, ignore=shutil.ignore_patterns("expected.json"))
    uid, gid = image_user_ids(name)
    for path in [src, *src.rglob("*")]:
        os.chown(path, uid, gid, follow_symlinks=False)
    results = []
    with ContainerWorkbench(name, src, log) as bench:
        api = bench.status("/api/status")
        lab = bench.status("/lab")
        anonymous = bench.status("/api/status", token=None)
        results.append(("make jupyter answers over HTTP", api == 200 and lab == 200 and anonymous == 403,
                        "/api/status %s, /lab %s with the token, /api/status %s without, %.1f s to answer"
                        % (api, lab, anonymous, bench.started_s)))
        started = time.monotonic()
        try:
            greeting = bench.desktop_greeting(DESKTOP_TIMEOUT_S).decode(errors="replace").strip()
        except Exception as err:  # noqa: BLE001 (whatever stops it is this check's FAIL, in words)
            greeting = "%s: %s" % (type(err).__name__, err)
        results.append(("the desktop's VNC server answers through /desktop-websockify/",
                        greeting.startswith("RFB 003."), "%r, %.1f s" % (greeting[:200], time.monotonic() - started)))
        started = time.monotonic()
        with bench.terminal() as terminal:
            code, output = terminal.run("course-check --only chatter", timeout=SELF_CHECK_TIMEOUT_S)
        with open(log, "a") as out:
            out.write("\n$ course-check --only chatter\n%s\n" % output)
        # the self-check's verdict line: "PASS  chatter: Example publisher and subscriber (...)"
        verdict = [line.strip() for line in output.splitlines() if re.match(r"(PASS|FAIL)\s+chatter:", line)]
        results.append(("course-check on a correct chatter package", code == 0 and len(verdict) == 1
                        and verdict[0].startswith("PASS"), "exit %d, %s, %.0f s" % (
                            code, verdict[-1] if verdict else "no chatter verdict", time.monotonic() - started)))
    return results
