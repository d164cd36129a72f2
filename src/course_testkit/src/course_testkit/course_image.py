"""The course image and the Gradescope autograder tried in real OCI containers (tests/e2e/test_image.py,
`make docker-check`, `make autograder-check`): what each step does and finds, one printed line per
check. The containers are course_testkit.podman's.

- the student image holds no answer: no file of a reference solution or a graded sample (by its
  content, anywhere in the image), no package.xml naming a reference package;
- `make lab` and `make jupyter` through their ports published on the host's loopback, as the
  README runs them: the lab page and its websocket, the workbench's terminals, course-check, the
  tokens;
- `make grade` of a class folder in the instructor image;
- Gradescope's setup.sh and run_autograder, each in a fresh container of the base image, and the
  results.json they leave against Gradescope's format and the expected verdict.

course_testkit's Jupyter and rosbridge clients need tornado alone, which Debian's python3 has;
course_sandbox.procs reads /proc; course_net is the standard library alone (course_checks.isolation,
which re-exports it, needs course_sandbox): Debian's python3 runs this without ROS sourced.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import secrets
import shlex
import shutil
import statistics
import subprocess
import time
import zipfile
from pathlib import Path
from typing import Dict, List, Optional, Tuple

from course_sandbox import procs
from course_testkit import student_lab
from course_testkit.jupyter import JupyterError, JupyterServer, refused_websocket
from course_testkit.podman import (BASE_IMAGE, CHECKOUT, COURSE_IMAGE, INSTRUCTOR_IMAGE, container_name, image_uid,
                                   last_line, network_mounts, podman, remove_container, run_in_image)
from course_testkit.rosbridge import drive_turtle
from course_net.ports import free_port
from course_checks.waiting import wait_for

AUTOGRADER_IMAGE = "localhost/ros-course-autograder"
# (sample, what it is, passed?) graded by run_autograder on the milestone `chatter`.
AUTOGRADER_SAMPLES = (("lab2_chatter_scripts", "correct", True), ("bad_crash", "buggy", False),
                      ("bad_build_error", "does not build", False), ("attack_forge_results", "attack", False))
JUPYTER_START_S = 120.0  # the limit for `make jupyter` in a container to answer
TARGET_START_S = 10.0  # the target for `docker run` to a usable JupyterLab
VISIBILITY = {"hidden", "after_due_date", "after_published", "visible"}
MIN_ANSWER_BYTES = 64  # smaller files (an empty __init__.py, a one-line .msg) are common to any package
COURSE = CHECKOUT / "courses" / "robotics_labs"
LOGS = CHECKOUT / "podman-logs"  # each step's log, by default


def reference_fingerprints() -> Dict[str, str]:
    """sha256 -> path of every file of the reference solutions (and the graded samples, which hold
    correct answers too) that says something: files of a few bytes (an empty __init__.py) are left out."""
    import hashlib

    def files(top: Path) -> Dict[str, str]:
        return {hashlib.sha256(p.read_bytes()).hexdigest(): str(p.relative_to(CHECKOUT)) for p in sorted(top.rglob("*"))
                if p.is_file() and not p.is_symlink() and "__pycache__" not in p.parts
                and p.stat().st_size >= MIN_ANSWER_BYTES}
    course = files(CHECKOUT / "src")  # a sample may copy a course file (an attack replacing course_testkit)
    for handout in CHECKOUT.glob("courses/*/starter"):  # or the code the texts hand out, which is no answer
        course.update(files(handout))
    found = {**files(COURSE / "solution"), **files(COURSE / "samples")}
    return {digest: path for digest, path in found.items() if digest not in course}


def answers_in_image(image: str, log: Path) -> List[str]:
    """The files of `image` that are a reference solution's (by content, anywhere in its file
    system) or a package.xml naming a reference package; [] for an image without the answers."""
    names = sorted(p.parent.name for p in (COURSE / "solution").glob("*/package.xml"))
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
    shutil.copytree(COURSE / "samples" / sample, submission)
    (submission / "expected.json").unlink()
    results.mkdir(parents=True)
    code = run_in_image(AUTOGRADER_IMAGE, ["/autograder/run_autograder"], log,
                        ["-v", "%s:/autograder/submission" % submission, "-v", "%s:/autograder/results" % results])
    path = results / "results.json"
    if not path.exists():
        return {}, ["run_autograder exited %s without results.json" % code]
    return json.loads(path.read_text()), []


def options(words: str) -> argparse.Namespace:
    """DOCKER_CHECK_ARGS (`make docker-check DOCKER_CHECK_ARGS="--rebuild --grade-class DIR"`)."""
    parser = argparse.ArgumentParser(prog="make docker-check DOCKER_CHECK_ARGS=")
    parser.add_argument("--rebuild", action="store_true", help="build twice: the second from cached layers")
    parser.add_argument("--skip-test", action="store_true", help="do not run make test in the container")
    parser.add_argument("--grade-class", metavar="DIR", help="also `make grade` this class folder in the image")
    parser.add_argument("--logs", type=Path, default=LOGS, help="where each step's log goes")
    return parser.parse_args(shlex.split(words))
