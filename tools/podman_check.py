#!/usr/bin/env python3
"""The course image and the Gradescope autograder tried in real OCI containers, built and run by
Debian's podman (as root: this machine's podman needs runc, cgroupfs and no default ulimits).

    sudo python3 tools/podman_check.py image                 # base image (once) + docker/Dockerfile's two images
    sudo python3 tools/podman_check.py docker-check          # both images: the demo, no answers in the
                                                             # student's; make grade and make test in the instructor's
    sudo python3 tools/podman_check.py jupyter-check [--runs 5]  # make jupyter in the built student image:
                                                             # the lab through its port; the start-up timed
    sudo python3 tools/podman_check.py autograder-check ZIP  # Gradescope's way, in containers

No image registry is reachable here, so `debian:bookworm` is imported once from a debootstrap
(minbase, the host's Debian mirror) and reused. Each step's wall time is printed at the end.
Where podman cannot run (not root, podman missing and not installable), this says why and exits
non-zero: there is no stand-in.

The host's CA bundle is lent to the containers read-only, with a pip.conf pointing at it, so that
pip reaches PyPI through this machine's TLS-intercepting proxy as the host's pip does; apt uses
plain http and needs nothing. Neither goes into an image.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import secrets
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

ROOT = Path(__file__).resolve().parents[1]
# course_testkit's Jupyter and rosbridge clients need tornado alone, which Debian's python3 has;
# course_sandbox.procs reads /proc.
sys.path[:0] = [str(ROOT / "src" / p / "src") for p in ("course_testkit", "course_checks", "course_sandbox")]
from course_sandbox import procs  # noqa: E402
from course_testkit import student_lab  # noqa: E402
from course_testkit.jupyter import JupyterError, JupyterServer, refused_websocket  # noqa: E402
from course_testkit.rosbridge import drive_turtle  # noqa: E402
# course_net is the standard library alone: imported by path, as Debian's python3 runs this
# without ROS sourced (course_checks.isolation, which re-exports it, needs course_sandbox).
sys.path.insert(0, str(ROOT / "src" / "course_net" / "src"))
from course_net.ports import free_port  # noqa: E402
from course_checks.waiting import wait_for  # noqa: E402
PODMAN = ["podman", "--runtime", "runc", "--cgroup-manager=cgroupfs"]
BASE_IMAGE = "debian:bookworm"
# The images' tags: $COURSE_IMAGE and $INSTRUCTOR_IMAGE name others (a second checkout's, say).
COURSE_IMAGE = os.environ.get("COURSE_IMAGE") or "localhost/ros-course"  # the student image (the default target)
INSTRUCTOR_IMAGE = os.environ.get("INSTRUCTOR_IMAGE") or "localhost/ros-course-instructor"  # with the answers
AUTOGRADER_IMAGE = "localhost/ros-course-autograder"
CONTAINERS_CONF = Path("/etc/containers/containers.conf")
HOST_CA = Path("/etc/ssl/certs/ca-certificates.crt")
CA_IN_CONTAINER = "/etc/ssl/certs/host-ca-bundle.crt"
PACKAGES = ("podman", "runc", "debootstrap")
# (sample, what it is, passed?) graded by run_autograder on the milestone `chatter`.
AUTOGRADER_SAMPLES = (("lab2_chatter_scripts", "correct", True), ("bad_crash", "buggy", False),
                      ("bad_build_error", "does not build", False), ("attack_forge_results", "attack", False))
JUPYTER_START_S = 120.0  # the limit for `make jupyter` in a container to answer
TARGET_START_S = 10.0  # the target for `docker run` to a usable JupyterLab
VISIBILITY = {"hidden", "after_due_date", "after_published", "visible"}
MIN_ANSWER_BYTES = 64  # smaller files (an empty __init__.py, a one-line .msg) are common to any package


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
        podman("build", "--network", "host", *network_mounts(scratch), "-f", str(ROOT / "docker" / "Dockerfile"),
               *(["--target", target] if target else []), "-t", INSTRUCTOR_IMAGE if target else COURSE_IMAGE,
               str(ROOT), log=log)


def reference_fingerprints() -> Dict[str, str]:
    """sha256 -> path of every file of the reference solutions (and the graded samples, which hold
    correct answers too) that says something: files of a few bytes (an empty __init__.py) are left out."""
    import hashlib

    def files(top: Path) -> Dict[str, str]:
        return {hashlib.sha256(p.read_bytes()).hexdigest(): str(p.relative_to(ROOT)) for p in sorted(top.rglob("*"))
                if p.is_file() and not p.is_symlink() and "__pycache__" not in p.parts
                and p.stat().st_size >= MIN_ANSWER_BYTES}
    course = files(ROOT / "src")  # a sample may copy a course file (an attack replacing course_testkit)
    for handout in ROOT.glob("courses/*/starter"):  # or the code the texts hand out, which is no answer
        course.update(files(handout))
    found = {**files(ROOT / "courses" / "robotics_labs" / "solution"), **files(ROOT / "courses" / "robotics_labs" / "samples")}
    return {digest: path for digest, path in found.items() if digest not in course}


def answers_in_image(image: str, log: Path) -> List[str]:
    """The files of `image` that are a reference solution's (by content, anywhere in its file
    system) or a package.xml naming a reference package; [] for an image without the answers."""
    names = sorted(p.parent.name for p in (ROOT / "courses" / "robotics_labs" / "solution").glob("*/package.xml"))
    script = ("find / -xdev -type f -size -4M -size +%dc -print0 | xargs -0 sha256sum; "
              "find / -xdev -name package.xml -print0 | xargs -0 grep -l -E '<name>(%s)</name>' | sed 's/^/xml /'"
              % (MIN_ANSWER_BYTES - 1, "|".join(names)))
    done = podman("run", "--rm", "--network", "none", "--user", "root", "--entrypoint", "bash", image, "-c", script,
                  check=False, stdout=subprocess.PIPE, text=True)
    log.write_text(done.stdout)
    fingerprints = reference_fingerprints()
    found = []
    for line in done.stdout.splitlines():
        digest, _, path = line.partition("  ")
        if digest == "xml" and "/starter/" not in path:  # a starter's package.xml is the handout's
            found.append("%s names a reference package" % path)
        elif digest in fingerprints:
            found.append("%s is %s" % (path, fingerprints[digest]))
    return found


def student_image_has_no_answers(log: Path) -> bool:
    found = answers_in_image(COURSE_IMAGE, log)
    control = answers_in_image(INSTRUCTOR_IMAGE, log.with_suffix(".instructor.log"))
    print("answers in the student image: %d file(s)%s; in the instructor's (the control): %d"
          % (len(found), "".join("\n  " + f for f in found[:20]), len(control)), flush=True)
    return not found and bool(control)


def run_in_image(image: str, command: Sequence[str], log: Path, extra: Sequence[str] = ()) -> int:
    """A fresh container of `image` (its own loopback-only network), removed afterwards; its exit code."""
    return podman("run", "--rm", "--network", "none", "--shm-size", "1g", *extra, image, *command,
                  check=False, log=log).returncode


def last_line(path: Path, pattern: str) -> str:
    lines = [line for line in path.read_text(errors="replace").splitlines() if re.search(pattern, line)]
    return lines[-1].strip() if lines else "(no such line)"


def docker_check(opts: argparse.Namespace, steps: Steps, scratch: Path, logs: Path) -> bool:
    steps.run("base image import", import_base, logs / "import.log")
    steps.run("image build", build_course_image, scratch, logs / "build.log")
    if opts.rebuild:
        steps.run("image build, again (cached layers)", build_course_image, scratch, logs / "build-again.log")
    ok = True
    code = steps.run("demo (the image's CMD, as user student)", run_in_image, COURSE_IMAGE, [], logs / "demo.log")
    print("demo: exit %s; %s" % (code, last_line(logs / "demo.log", r"\S")), flush=True)
    ok &= code == 0
    ok &= steps.run("no reference solution in the student image", student_image_has_no_answers,
                    logs / "answers.log")
    ok &= steps.run("lab page through a published port", lab_check, logs / "lab.log")
    ok &= steps.run("make jupyter through a published port, as user student", jupyter_check, scratch,
                    logs / "jupyter.log")
    code = steps.run("make grade (the reference) in the instructor image, as user student", run_in_image,
                     INSTRUCTOR_IMAGE, ["make", "grade", "GRADES=/tmp/grades"], logs / "grade-reference.log")
    print("make grade: exit %s; %s" % (code, last_line(logs / "grade-reference.log", r"^\[1/1\] reference")),
          flush=True)
    ok &= code == 0
    if opts.grade_class:
        ok &= steps.run("make grade of %s in a container, as root" % opts.grade_class, grade_class,
                        Path(opts.grade_class).resolve(), scratch, logs / "grade.log")
    if not opts.skip_test:
        code = steps.run("make test in the instructor image, as user student", run_in_image, INSTRUCTOR_IMAGE,
                         ["make", "test"], logs / "test.log")
        print("make test: exit %s; %s" % (code, last_line(logs / "test.log", r"passed|failed|error")), flush=True)
        ok &= code == 0
    return ok


def grade_class(folder: Path, scratch: Path, log: Path) -> bool:
    """A TA's `make grade` in the image: the class folder read-only, the grades folder writable."""
    grades = scratch / "grades"
    grades.mkdir()
    code = run_in_image(INSTRUCTOR_IMAGE, ["make", "grade", "SUBMISSIONS=/class", "GRADES=/grades"], log,
                        ["--user", "root", "-v", "%s:/class:ro" % folder, "-v", "%s:/grades" % grades])
    gradebook = grades / "gradebook.csv"
    rows = gradebook.read_text().splitlines()[1:] if gradebook.exists() else []
    print("make grade: exit %s; %d students in gradebook.csv; %s" % (
        code, len(rows), last_line(log, r"^isolation: ")), flush=True)
    return bool(rows)


def http_status(url: str) -> Tuple[int, str]:
    import urllib.error
    import urllib.request
    try:
        with urllib.request.urlopen(url, timeout=10) as answer:
            return answer.status, answer.read().decode("utf-8", "replace")
    except urllib.error.HTTPError as e:
        return e.code, ""


def lab_check(log: Path) -> bool:
    """`make lab` in a container with its port published on the host's loopback: the URL it prints,
    the page through the published port with the token, refused without it, the turtle moved
    through the page's websocket."""
    port = free_port()
    name = container_name("lab-check")
    remove_container(name)
    podman("run", "-d", "--name", name, "-p", "127.0.0.1:%d:8080" % port, COURSE_IMAGE, "make", "lab", log=log)
    try:
        deadline = time.monotonic() + 120
        url = None
        while url is None and time.monotonic() < deadline:
            out = podman("logs", name, check=False, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
            m = re.search(r"lab_view: open (http://127\.0\.0\.1:8080/\?token=\S+)", out)
            url = m.group(1).replace(":8080/", ":%d/" % port) if m else None
            time.sleep(0.5)
        if url is None:
            print("lab: no URL with a token printed within 120 s", flush=True)
            return False
        with_token, page = http_status(url)
        without, _ = http_status("http://127.0.0.1:%d/" % port)
        before, after = drive_turtle(url.replace("http://", "ws://", 1))
        ok = with_token == 200 and "<html" in page.lower() and without in (401, 403) and after - before > 0.5
        print("lab: %s -> %d; without the token -> %d; turtle1 x %.2f -> %.2f driven through the page's "
              "websocket" % (re.sub(r"token=\S+", "token=...", url), with_token, without, before, after), flush=True)
        return ok
    finally:
        podman("logs", name, check=False, log=log)
        remove_container(name)


def image_uid(image: str) -> int:
    """The uid the image's user has (the volume is handed to it, as a student's own folder is theirs)."""
    return int(podman("run", "--rm", "--network", "none", "--entrypoint", "id", image, "-u",
                      stdout=subprocess.PIPE, text=True).stdout.strip())


class Checks:
    """One printed line per check, and whether all passed."""

    def __init__(self, prefix: str) -> None:
        self.prefix, self.ok = prefix, True

    def __call__(self, passed: bool, line: str) -> bool:
        self.ok &= bool(passed)
        print("%s: %s %s" % (self.prefix, "ok    " if passed else "FAILED", line), flush=True)
        return bool(passed)


def usable_after(server: JupyterServer, began: float, name: str) -> Optional[Tuple[float, float]]:
    """Seconds from `began` until the server's REST API answers, and until a new terminal has run a
    command; None when the container ends or JUPYTER_START_S passes first."""
    polls = iter(range(1 << 30))

    def answering() -> bool:
        if server.status("/api/status") == 200:
            return True
        if next(polls) % 40 == 39:  # now and then (podman is slow to ask): has the container ended?
            running = podman("container", "inspect", "-f", "{{.State.Running}}", name, check=False,
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.strip()
            if running != "true":
                raise JupyterError("the container %s stopped" % name)
        return False
    if not wait_for(answering, JUPYTER_START_S, 0.05):
        return None
    rest = time.monotonic() - began
    with server.terminal() as term:
        term.run("true")
    return rest, time.monotonic() - began


def start_workbench(server: JupyterServer, name: str, work: Path, log: Path) -> Optional[Tuple[float, ...]]:
    """`make jupyter` in a container `name` of the student image as the README says: the port
    published on the host's loopback, `work` mounted as ~/catkin_ws/src, JUPYTER_TOKEN set (from
    podman's environment: not on a command line). Seconds from `podman run` to its return, to
    REST answering and to a terminal's first command, and the load average before; None when it
    did not start."""
    remove_container(name)
    load = os.getloadavg()[0]
    began = time.monotonic()
    podman("run", "-d", "--name", name, "-p", "127.0.0.1:%d:8888" % server.port, "-e", "JUPYTER_TOKEN",
           "-v", "%s:/home/student/catkin_ws/src" % work, COURSE_IMAGE, "make", "jupyter", log=log,
           env=dict(os.environ, JUPYTER_TOKEN=server.token))
    created = time.monotonic() - began
    times = usable_after(server, began, name)
    if times is None:
        return None
    pid = podman("inspect", "-f", "{{.State.Pid}}", name, stdout=subprocess.PIPE, text=True).stdout.strip()
    return (created, *times, load, tree_cpu_seconds(int(pid)))


def tree_cpu_seconds(pid: int) -> float:
    """CPU seconds used by `pid` and every process below it, the ended ones included: a
    container's start-up's cost, whatever the machine's load."""
    return sum(procs.cpu_with_ended_children(p) or 0.0 for p in [pid] + procs.descendants(pid))


def start_figure(times: Optional[Tuple[float, ...]]) -> str:
    """The start-up's figure, not a verdict: a loaded machine may miss the target and still work."""
    if times is None:
        return "not within %.0f s" % JUPYTER_START_S
    created, rest, usable, load, cpu = times
    return ("podman run -d returned after %.1f s, REST answered after %.1f s, a terminal ran a command after %.1f s "
            "(%s the target <= %.0f s; load average %.1f before); the container's processes used %.1f CPU s"
            % (created, rest, usable, "meets" if usable <= TARGET_START_S else "MISSES", TARGET_START_S, load, cpu))


def jupyter_starts(runs: int, scratch: Path, log: Path) -> bool:
    """The start-up alone, `runs` times (each a fresh container and an empty folder): each run's
    figure, then the median and the worst."""
    usable: List[float] = []
    cpus: List[float] = []
    for run in range(runs):
        work = scratch / ("start-%d" % run)
        work.mkdir()
        os.chown(work, *(2 * [image_uid(COURSE_IMAGE)]))
        name = container_name("jupyter-start")
        try:
            times = start_workbench(JupyterServer(free_port(), secrets.token_hex(16)), name, work, log)
        finally:
            remove_container(name)
        print("jupyter start %d: %s" % (run + 1, start_figure(times)), flush=True)
        if times is None:
            return False
        usable.append(times[2])
        cpus.append(times[4])
    print("jupyter start: podman run to a usable JupyterLab, median %.1f s, worst %.1f s over %d runs (target <= "
          "%.0f s); CPU used, median %.1f s" % (statistics.median(usable), max(usable), runs, TARGET_START_S,
                                              statistics.median(cpus)), flush=True)
    return True


def jupyter_check(scratch: Path, log: Path) -> bool:
    """`make jupyter` in the student image (start_workbench), then through the published port what
    the workbench's tests do on the host: a lab in a terminal and the contents API, the self-check
    passing it and failing a buggy copy with its reason, the lab page and its websocket, and a
    wrong or missing token refused. One line per check."""
    check = Checks("jupyter")
    work = scratch / "work"
    work.mkdir()
    uid = image_uid(COURSE_IMAGE)
    os.chown(work, uid, uid)
    server, name = JupyterServer(free_port(), secrets.token_hex(16)), container_name("jupyter-check")
    try:
        times = start_workbench(server, name, work, log)
        if not check(times is not None, "podman run to a usable JupyterLab: " + start_figure(times)):
            return False
        with server.terminal() as term:
            student_lab.make_chatter(server, term)  # each step must succeed, or JupyterError
            talker = work / "chatter" / "scripts" / "talker.py"
            check(talker.exists() and talker.stat().st_uid == uid,
                  "catkin_create_pkg chatter rospy std_msgs in a terminal, the talker and the listener through the "
                  "contents API, catkin_make: built; %s on the host's folder, owner uid %s"
                  % (talker.relative_to(work), talker.stat().st_uid if talker.exists() else "-"))
            code, said = term.run("course-check", student_lab.CHECK_TIMEOUT_S)
            isolation = re.search(r"isolation: ([^:\n]+)", said)
            check(code == 0 and student_lab.PASSED in said, "course-check: exit %d, %r; isolation %s" % (
                code, student_lab.PASSED if student_lab.PASSED in said else said[-300:],
                isolation.group(1) if isolation else "not said"))
            buggy = student_lab.make_buggy_copy(server, term)
            code, said = term.run("course-check ~/%s --out ~/buggy-check" % buggy, student_lab.CHECK_TIMEOUT_S)
            check(code == 1 and student_lab.FAILED in said and student_lab.BUGGY_REASON in said,
                  "course-check of a talker on the wrong topic: exit %d, %s" % (
                      code, "FAIL with '%s'" % student_lab.BUGGY_REASON if student_lab.BUGGY_REASON in said
                      else said[-300:]))
        status, page, _ = server.request("GET", "/roslab/")
        check(status == 200 and b"<html" in page.lower(), "/roslab/ with the token -> %d" % status)
        ws = "ws://127.0.0.1:%d/roslab/websocket" % server.port
        before, after = drive_turtle("%s?token=%s" % (ws, server.token))
        check(after - before > 1.0, "turtle1 x %.2f -> %.2f driven through /roslab/websocket" % (before, after))
        refused = {"/api/contents, wrong token": server.status("/api/contents", token="not-the-token"),
                   "/api/contents, no token": server.status("/api/contents", token=None),
                   "/roslab/, wrong token": server.status("/roslab/", token="not-the-token"),
                   "/roslab/websocket, wrong token": refused_websocket(ws + "?token=not-the-token"),
                   "/roslab/websocket, no token": refused_websocket(ws)}
        check(all(code in (302, 401, 403) for code in refused.values()), "refused: " + ", ".join(
            "%s -> %s" % (what, code) for what, code in refused.items()))
    except (JupyterError, OSError) as err:
        check(False, "%s" % str(err)[-2000:])
    finally:
        podman("logs", name, check=False, log=log)
        remove_container(name)
    return check.ok


def unpack_zip(zip_path: Path, target: Path) -> None:
    """As Gradescope does (unzip keeps the modes the zip records; zipfile does not)."""
    with zipfile.ZipFile(zip_path) as zf:
        for info in zf.infolist():
            path = Path(zf.extract(info, target))
            mode = (info.external_attr >> 16) & 0o777
            if mode:
                path.chmod(mode)


def build_autograder_image(zip_path: Path, scratch: Path, log: Path) -> None:
    """A fresh container of the base image, the zip in /autograder/source, setup.sh as root;
    committed as the image every submission is graded in."""
    source = scratch / "source"
    unpack_zip(zip_path, source)
    name = container_name("autograder-setup")
    remove_container(name)
    script = ("set -e; mkdir -p /autograder/results; cp -a /mnt/source /autograder/source; "
              "bash /autograder/source/setup.sh; cp /autograder/source/run_autograder /autograder/run_autograder")
    try:
        podman("run", "--name", name, "--network", "host", *network_mounts(scratch),
               "-v", "%s:/mnt/source:ro" % source, BASE_IMAGE, "bash", "-c", script, log=log)
        podman("commit", name, AUTOGRADER_IMAGE, log=log)
    finally:
        remove_container(name)


def results_problems(results: Dict, passed: bool) -> List[str]:
    """What is wrong with a results.json against Gradescope's format and the expected verdict."""
    problems = []
    if not isinstance(results.get("score"), (int, float)):
        problems.append("score is not a number")
    if results.get("visibility", "visible") not in VISIBILITY:
        problems.append("visibility %r" % results.get("visibility"))
    tests = results.get("tests") or []
    if not tests:
        problems.append("no tests")
    for test in tests:
        for key, kind in (("name", str), ("output", str), ("score", (int, float)), ("max_score", (int, float))):
            if not isinstance(test.get(key), kind):
                problems.append("test %r: %s missing or not %s" % (test.get("name"), key, kind))
        want = "passed" if passed else "failed"
        if test.get("status") != want:
            problems.append("test %r: %s, expected %s" % (test.get("name"), test.get("status"), want))
    if "isolation: " not in results.get("output", ""):
        problems.append("the output does not say which isolation was in force")
    return problems


def grade_in_container(sample: str, scratch: Path, log: Path) -> Tuple[Dict, List[str]]:
    """run_autograder on one sample, in a fresh container of the autograder image, as root."""
    submission = scratch / "submissions" / sample
    results = scratch / "results" / sample
    shutil.copytree(ROOT / "courses" / "robotics_labs" / "samples" / sample, submission)
    (submission / "expected.json").unlink()
    results.mkdir(parents=True)
    code = run_in_image(AUTOGRADER_IMAGE, ["/autograder/run_autograder"], log,
                        ["-v", "%s:/autograder/submission" % submission, "-v", "%s:/autograder/results" % results])
    path = results / "results.json"
    if not path.exists():
        return {}, ["run_autograder exited %s without results.json" % code]
    return json.loads(path.read_text()), []


def autograder_check(opts: argparse.Namespace, steps: Steps, scratch: Path, logs: Path) -> bool:
    zip_path = Path(opts.zip).resolve()
    with zipfile.ZipFile(zip_path) as zf:
        milestones = zf.read("milestones.txt").decode().split() if "milestones.txt" in zf.namelist() else []
    if milestones != ["chatter"]:
        raise Unavailable("%s must grade the milestone chatter alone (make autograder MILESTONES=chatter), "
                          "not %s" % (zip_path, milestones or "every milestone"))
    steps.run("base image import", import_base, logs / "import.log")
    steps.run("setup.sh as root in a fresh container", build_autograder_image, zip_path, scratch,
              logs / "setup.log")
    ok = True
    for sample, what, passed in AUTOGRADER_SAMPLES:
        results, problems = steps.run("run_autograder: %s (%s)" % (sample, what), grade_in_container, sample,
                                      scratch, logs / ("grade-%s.log" % sample))
        problems = problems or results_problems(results, passed)
        isolation = re.search(r"isolation: ([^:\n]+)", results.get("output", ""))
        print("%s: score %s, %s; isolation %s%s" % (
            sample, results.get("score"), ", ".join("%s %s" % (t.get("name", "?").split(":")[0], t.get("status"))
                                                    for t in results.get("tests", [])),
            isolation.group(1) if isolation else "?", "; PROBLEMS: " + "; ".join(problems) if problems else ""),
            flush=True)
        ok &= not problems
    return ok


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="action", required=True)
    image = sub.add_parser("image", help="import the base image (once) and build docker/Dockerfile")
    image.add_argument("--rebuild", action="store_true", help="build twice: the second from cached layers")
    check = sub.add_parser("docker-check", help="the image, its CMD, then make test in a container")
    check.add_argument("--rebuild", action="store_true", help="build twice: the second from cached layers")
    check.add_argument("--skip-test", action="store_true", help="do not run make test in the container")
    check.add_argument("--grade-class", metavar="DIR", help="also `make grade` this class folder in the image")
    jupyter = sub.add_parser("jupyter-check", help="make jupyter in the student image already built (no build): "
                             "the lab through its published port, then the start-up --runs more times")
    jupyter.add_argument("--runs", type=int, default=0, help="start-ups to time after the check (default none)")
    grader = sub.add_parser("autograder-check", help="Gradescope's setup.sh and run_autograder in containers")
    grader.add_argument("zip", help="autograder.zip made with MILESTONES=chatter")
    parser.add_argument("--logs", default=str(ROOT / "podman-logs"), help="where each step's log goes")
    opts = parser.parse_args(argv)
    actions = {"image": image_action, "docker-check": docker_check, "jupyter-check": jupyter_check_action,
               "autograder-check": autograder_check}
    return run_action("podman_check", opts, actions[opts.action], Path(opts.logs))


def image_action(opts: argparse.Namespace, steps: Steps, scratch: Path, logs: Path) -> bool:
    steps.run("base image import", import_base, logs / "import.log")
    steps.run("image build", build_course_image, scratch, logs / "build.log")
    if opts.rebuild:
        steps.run("image build, again (cached layers)", build_course_image, scratch, logs / "build-again.log")
    return True


def jupyter_check_action(opts: argparse.Namespace, steps: Steps, scratch: Path, logs: Path) -> bool:
    ok = steps.run("make jupyter through a published port, as user student", jupyter_check, scratch,
                   logs / "jupyter.log")
    if opts.runs:
        ok &= steps.run("make jupyter's start-up, %d times" % opts.runs, jupyter_starts, opts.runs, scratch,
                        logs / "jupyter-starts.log")
    return ok


def run_action(tool: str, opts: argparse.Namespace, action, logs: Path) -> int:
    """`action(opts, steps, scratch, logs)` with podman ready, a scratch folder removed afterwards,
    and each step's time printed at the end; the exit code (2: podman cannot run here)."""
    logs.mkdir(parents=True, exist_ok=True)
    steps = Steps()
    scratch = Path(tempfile.mkdtemp(prefix="%s-" % tool))
    scratch.chmod(0o755)
    try:
        ensure_podman()
        ok = action(opts, steps, scratch, logs)
    except Unavailable as e:
        print("%s: %s" % (tool, e), file=sys.stderr)
        return 2
    except subprocess.CalledProcessError as e:
        print("%s: %s failed (exit %s); see the logs in %s" % (tool, " ".join(map(str, e.cmd))[:200],
                                                               e.returncode, logs), file=sys.stderr)
        ok = False
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    print(steps.table())
    print("%s %s: %s (logs in %s)" % (tool, opts.action, "ok" if ok else "FAILED", logs))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
