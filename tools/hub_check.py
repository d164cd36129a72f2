#!/usr/bin/env python3
"""`make hub-check`: the class's hub end to end, with real parts (root, podman).

    sudo make hub-check                                   # builds the student image, then checks
    sudo make hub-check HUB_CHECK_ARGS="--image localhost/ros-course-hub --no-build"

The student image (docker/Dockerfile's default target), `make hub`'s own start (course_hub's
runner: podman's Docker API on a socket of its own, JupyterHub with deploy/jupyterhub's config,
a class list of a TA and four students, a scratch data folder), then the students at their
browsers (course_testkit.hub: the login form with its _xsrf, cookies, the hub's OAuth to each
server, terminals through the hub's proxy):

- alice, bob and carol log in (their first login sets their password; a wrong one is refused
  then, and a name not on the class list is refused), start their servers, and run roscore and
  turtlesim in a terminal of their workbench;
- alice's rostopic/rosnode list shows her turtlesim and none of the others'; her
  `pkill -f turtlesim` ends hers and leaves bob's running;
- alice cannot open bob's server, its REST API or its terminals through the hub, nor connect to
  his container's ports (the Jupyter server, a port bob listens on) which the hub's host reaches;
- tom (a TA, the hub's admin) opens bob's server and sees bob's turtlesim in a terminal there;
- dave's server fails to start (the check gives him a memory limit too small for the
  workbench): the hub says why, and alice's server still answers;
- the idle culler (jupyterhub-idle-culler against the hub's API) stops the idle servers; alice
  starts again and finds her files;
- `hub_grade` snapshots the class and grades it: alice's chatter (tests/submissions'
  lab2_chatter_scripts, chmod +x in her terminal) passes, bob's (lab2_chatter_no_chmod) fails
  with its reason, carol (nothing) gets no points; each reads their own report in ~/grades of
  their workbench, read-only, and only their own.

One line per check, the last `hub check K/N`; exit code 0 when all passed. Everything it
started is stopped and removed at the end (--keep leaves the data folder).
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import traceback
from pathlib import Path
from typing import Callable, Dict, List, Optional

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
from podman_check import PODMAN, network_mounts  # noqa: E402

from course_hub import passwords as hub_passwords  # noqa: E402
from course_testkit.hub import HubUser, LocalHub, SpawnFailed  # noqa: E402
from course_testkit.jupyter import Terminal  # noqa: E402
from course_testkit.waiting import wait_for  # noqa: E402

STUDENTS = ("alice", "bob", "carol")
FAILING = "dave"        # a student whose server cannot start (a memory limit too small)
TA = "tom"
TOO_LITTLE_MEMORY = "8M"  # JupyterLab cannot answer in it (24M sometimes did, then died)
MILESTONE = "chatter"
SAMPLES = ROOT / "tests" / "submissions"
FILES = {"alice": SAMPLES / "lab2_chatter_scripts" / "lab2" / "src" / "chatter",
         "bob": SAMPLES / "lab2_chatter_no_chmod" / "chatter"}
# dave's server is given too little memory to start
CHECK_CONFIG = '''course_limit = c.DockerSpawner.mem_limit
c.DockerSpawner.mem_limit = lambda spawner: %(small)r if spawner.user.name == %(failing)r else course_limit
''' % {"small": TOO_LITTLE_MEMORY, "failing": FAILING}


class Report:
    """One line per check; the count at the end."""

    def __init__(self) -> None:
        self.passed = 0
        self.total = 0

    def check(self, name: str, ok: bool, detail: str = "") -> bool:
        self.total += 1
        self.passed += bool(ok)
        print("%s %s%s" % ("ok  " if ok else "FAIL", name, (": " + detail) if detail else ""), flush=True)
        return ok

    def attempt(self, name: str, fn: Callable[[], str]) -> bool:
        """A check whose function returns its detail, or raises (AssertionError: failed)."""
        try:
            return self.check(name, True, fn())
        except Exception as err:  # every failure becomes the check's line
            detail = str(err) or type(err).__name__
            if not isinstance(err, AssertionError):
                detail = "%s: %s" % (type(err).__name__, detail)
            return self.check(name, False, detail.replace("\n", " | ")[:1500])


def build_image(image: str, log: Path) -> None:
    scratch = Path(tempfile.mkdtemp(prefix="hub-check-build-"))
    try:
        with open(log, "ab") as out:
            subprocess.run(["nice", "-n", "10"] + PODMAN + ["build", "--network", "host", *network_mounts(scratch),
                           "-f", str(ROOT / "docker" / "Dockerfile"), "-t", image, str(ROOT)],
                           check=True, stdout=out, stderr=subprocess.STDOUT)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def podman_out(*args: str) -> str:
    return subprocess.run(PODMAN + list(args), check=False, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                          text=True).stdout.strip()


def container_ip(user: str) -> str:
    return podman_out("inspect", "course-hub-%s" % user, "-f", "{{range .NetworkSettings.Networks}}{{.IPAddress}}{{end}}")


def host_connects(ip: str, port: int) -> bool:
    try:
        with socket.create_connection((ip, port), timeout=3):
            return True
    except OSError:
        return False


CONNECT = ("python3 -c \"import socket,sys; s=socket.socket(); s.settimeout(3); "
           "sys.exit(0 if s.connect_ex(('%s', %d)) == 0 else 7)\"")


def upload(user: HubUser, folder: Path, target: str) -> int:
    """The files of `folder` written under `target` through the contents API (the file browser's upload)."""
    count = 0
    user.make_folder(target)
    for path in sorted(folder.rglob("*")):
        rel = "%s/%s" % (target, path.relative_to(folder).as_posix())
        if path.is_dir():
            user.make_folder(rel)
        else:
            user.write_file(rel, path.read_text())
            count += 1
    return count


def run(opts: argparse.Namespace) -> int:
    report = Report()
    work = Path(tempfile.mkdtemp(prefix="hub-check-"))
    os.chmod(work, 0o755)
    started = time.monotonic()
    if not opts.no_build:
        report.attempt("image %s built from docker/Dockerfile" % opts.image,
                       lambda: (build_image(opts.image, work / "build.log"), "log in %s" % (work / "build.log"))[1])
    hub = LocalHub(opts.image, work, STUDENTS + (FAILING,), (TA,), CHECK_CONFIG)
    users: Dict[str, HubUser] = {}
    terms: Dict[str, object] = {}
    passwords: Dict[str, str] = {}
    try:
        if not report.attempt("make hub's runner starts JupyterHub with deploy/jupyterhub's config", hub.start):
            print(hub.tail())
            return finish(report, started)
        # the initial passwords the hub gave the class list at its start (its hand-out sheet)
        passwords.update(hub_passwords.handed_out(str(hub.data)))
        for name in STUDENTS + (TA,):
            users[name] = HubUser(hub.url, name, passwords[name])

        def logins() -> str:
            assert sorted(passwords) == sorted(STUDENTS + (FAILING, TA)), sorted(passwords)
            # before anyone logged in: a classmate cannot claim alice's name with a password of their own
            claim = HubUser(hub.url, "alice", secrets.token_urlsafe(12))
            wrong = HubUser(hub.url, "alice", "not-" + passwords["alice"])
            stranger = HubUser(hub.url, "mallory", "whatever-she-likes")
            for intruder in (claim, wrong, stranger):
                try:
                    intruder.login()
                except Exception:
                    continue
                raise AssertionError("%s logged in with a password that is not theirs" % intruder.name)
            for user in users.values():
                user.login()
            return ("%d users on the hand-out sheet; 4 log in with theirs; claiming a listed name first, a wrong "
                    "password and a name off the list refused" % len(passwords))
        report.attempt("each user logs in through the hub's form (xsrf, cookies)", logins)

        spawn_times: Dict[str, float] = {}

        def spawns() -> str:
            for name in STUDENTS:
                spawn_times[name] = users[name].start()
                status, url = users[name].open_server()
                assert status == 200 and "/user/%s/lab" % name in url, (name, status, url)
            return ", ".join("%s %.1f s" % kv for kv in spawn_times.items())
        report.attempt("each student starts their server and opens JupyterLab through the hub", spawns)

        def turtlesims() -> str:
            for name in STUDENTS:
                term = terms[name] = users[name].terminal()
                code, said = term.run("(roscore > ~/roscore.log 2>&1 &) ; "
                                      "(rosrun turtlesim turtlesim_node __name:=turtlesim_%s > ~/turtlesim.log 2>&1 &)"
                                      % name)
                assert code == 0, said
            for name in STUDENTS:
                term = terms[name]
                assert wait_for(lambda: "/turtlesim_%s" % name in term.run("rosnode list 2>&1")[1], 90, 0.5), \
                    term.run("cat ~/turtlesim.log ~/roscore.log")[1][-1500:]
            return "roscore and turtlesim_<name> running in each student's terminal (websocket through the hub)"
        if not report.attempt("each student runs turtlesim in a terminal", turtlesims):
            return finish(report, started)

        def own_graph() -> str:
            code, nodes = terms["alice"].run("rosnode list")
            code2, topics = terms["alice"].run("rostopic list")
            assert "/turtlesim_alice" in nodes and "/turtle1/pose" in topics, nodes + topics
            others = [n for n in STUDENTS if n != "alice" and "turtlesim_%s" % n in nodes + topics]
            assert not others, "alice sees the nodes of %s: %s" % (others, nodes)
            return "rosnode list: %s" % " ".join(nodes.split())
        report.attempt("alice's rostopic/rosnode list shows none of bob's or carol's nodes", own_graph)

        def pkill() -> str:
            terms["alice"].run("pkill -f turtlesim")
            assert wait_for(lambda: terms["alice"].run("pgrep -f turtlesim_node")[0] != 0, 20, 0.2), \
                "alice's turtlesim still runs"
            code, said = terms["bob"].run("pgrep -f turtlesim_node && timeout 10 rostopic echo -n1 /turtle1/pose")
            assert code == 0 and "theta" in said, said
            return "alice's turtlesim ended; bob's still publishes /turtle1/pose"
        report.attempt("alice's pkill -f turtlesim leaves bob's turtlesim running", pkill)

        def no_way_to_bob() -> str:
            alice = users["alice"]
            status, url = alice.open_server("bob")
            assert status in (403, 404) or "/user/bob/" not in url, ("lab", status, url)
            as_bob = alice.as_session("bob")
            rest = as_bob.request("GET", "/api/contents/")[0]
            term = as_bob.request("POST", "/api/terminals")[0]
            assert rest >= 400 and term >= 400, ("REST", rest, "terminals", term)
            try:
                Terminal(as_bob, "1").close()
            except Exception:
                pass
            else:
                raise AssertionError("alice opened bob's terminal websocket")
            return "bob's lab %d, REST %d, new terminal %d, terminal websocket refused" % (status, rest, term)
        report.attempt("alice cannot reach bob's server or terminals through the hub", no_way_to_bob)

        def no_port_of_bob() -> str:
            ip = container_ip("bob")
            assert ip, "no address of bob's container"
            code, said = terms["bob"].run("(python3 -m http.server 9999 --bind 0.0.0.0 > /dev/null 2>&1 &)")
            assert wait_for(lambda: host_connects(ip, 9999), 20, 0.2), "the hub's host cannot reach bob's port 9999"
            assert host_connects(ip, 8888), "the hub's host cannot reach bob's Jupyter port"
            reached = [port for port in (8888, 9999, 11311) if terms["alice"].run(CONNECT % (ip, port))[0] == 0]
            assert not reached, "alice's container connected to bob's %s port(s) %s" % (ip, reached)
            return "bob's %s ports 8888, 9999 (which the hub's host reaches) and 11311: no connection from alice's" % ip
        report.attempt("alice's container cannot connect to bob's ports", no_port_of_bob)

        def admin() -> str:
            tom = users[TA]
            status, url = tom.open_server("bob")
            assert status == 200 and "/user/bob/lab" in url, (status, url)
            with tom.as_session("bob").terminal() as term:
                code, said = term.run("whoami; rosnode list")
            assert "/turtlesim_bob" in said, said
            return "tom opened /user/bob/lab and a terminal there: %s" % " ".join(said.split())
        report.attempt("the TA (admin) reaches bob's server and terminal", admin)

        def failed_start() -> str:
            dave = HubUser(hub.url, FAILING, passwords[FAILING])
            dave.login()
            try:
                dave.start(timeout=300)
            except SpawnFailed as err:
                message = str(err)
            else:
                raise AssertionError("dave's server started with %s of memory" % TOO_LITTLE_MEMORY)
            assert "ran out of memory" in message and TOO_LITTLE_MEMORY in message, "not clear: %s" % message
            assert users["alice"].request("GET", "/api/status")[0] == 200, "alice's server stopped answering"
            code, said = terms["bob"].run("pgrep -f turtlesim_node")
            assert code == 0, "bob's turtlesim is gone"
            return "the hub told dave: %s" % message
        report.attempt("a server that fails to start says why, the others unaffected", failed_start)

        def files() -> str:
            counts = {}
            for name, folder in FILES.items():
                counts[name] = upload(users[name], folder, "catkin_ws/src/chatter")
            code, said = terms["alice"].run("chmod +x ~/catkin_ws/src/chatter/scripts/*.py && ls -l ~/catkin_ws/src/chatter/scripts")
            assert code == 0, said
            return "uploaded %s; alice did chmod +x" % counts
        report.attempt("alice and bob write their chatter package in the workbench", files)

        for term in terms.values():
            term.close()
        terms.clear()

        def culled() -> str:
            culler = subprocess.Popen(
                [str(ROOT / ".venv-hub" / "bin" / "python3"), "-m", "jupyterhub_idle_culler", "--timeout=1",
                 "--cull-every=2", "--url=%s/hub/api" % hub.url],
                env=dict(os.environ, JUPYTERHUB_API_TOKEN=hub.culler_token), stdout=subprocess.DEVNULL,
                stderr=subprocess.STDOUT, start_new_session=True)
            try:
                gone = wait_for(lambda: not any(users[n].server_state() for n in STUDENTS), 120, 1.0)
            finally:
                os.killpg(culler.pid, signal.SIGTERM)
                culler.wait(30)
            assert gone, "still running: %s" % [n for n in STUDENTS if users[n].server_state()]
            assert not podman_out("ps", "-q", "--filter", "name=course-hub-alice"), "alice's container is still there"
            seconds = users["alice"].start()
            status, url = users["alice"].open_server()  # a new server: the hub's OAuth again
            assert status == 200 and "/user/alice/lab" in url, (status, url)
            status, data, _ = users["alice"].request("GET", "/api/contents/catkin_ws/src/chatter/package.xml")
            assert status == 200 and b"chatter" in data, (status, data[:300])
            with users["alice"].terminal() as term:
                code, said = term.run("test -x ~/catkin_ws/src/chatter/scripts/talker_node.py && pgrep -f turtlesim_node")
            assert code != 0, "after the cull: %s" % said
            return "all three culled (containers removed); alice back in %.1f s with her files, a fresh container" % seconds
        report.attempt("the idle culler stops idle servers; alice's files survive", culled)

        grades: Dict[str, Dict] = {}

        def grading() -> str:
            done = subprocess.run(["rosrun", "course_hub", "hub_grade", "--data", str(hub.data), "--class-list",
                                   str(hub.class_list), "--only", MILESTONE, "--stamp", "deadline"],
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
            book = hub.data / "grades" / "deadline" / "gradebook.csv"
            assert book.is_file(), done.stdout[-2000:]
            with open(book) as rows:
                for row in csv.DictReader(rows):
                    grades[row.get("student") or next(iter(row.values()))] = row
            assert set(STUDENTS) <= set(grades), "gradebook rows: %s" % sorted(grades)
            snap = hub.data / "snapshots" / "deadline" / "alice" / "chatter" / "package.xml"
            assert snap.is_file() and not os.access(snap, os.W_OK) or os.geteuid() == 0 and not snap.stat().st_mode & 0o222, \
                "the snapshot is writable"
            return "gradebook rows %s" % sorted(grades)
        report.attempt("hub_grade snapshots the class read-only and grades it, keyed by hub user", grading)

        def verdicts() -> str:
            results = {}
            for name in STUDENTS:
                path = hub.data / "grades" / "deadline" / name / "results.json"
                results[name] = json.loads(path.read_text()) if path.is_file() else {}
            alice_tests = {t["name"]: t for t in results["alice"].get("tests", [])}
            bob_tests = {t["name"]: t for t in results["bob"].get("tests", [])}
            assert any(t["status"] == "passed" and MILESTONE in n for n, t in alice_tests.items()), alice_tests
            bob_failed = [t for n, t in bob_tests.items() if MILESTONE in n]
            assert bob_failed and bob_failed[0]["status"] == "failed" and "not executable" in bob_failed[0]["output"], \
                bob_tests
            assert not results["carol"].get("score"), results["carol"]
            return "alice %s, bob %s (not executable), carol %s" % (
                results["alice"].get("score"), results["bob"].get("score"), results["carol"].get("score"))
        report.attempt("each student gets the verdict their files earn", verdicts)

        def own_report() -> str:
            alice = users["alice"]
            status, data, _ = alice.request("GET", "/api/contents/grades/deadline/report.txt")
            assert status == 200 and b"PASS" in data, (status, data[:400])
            status, listing, _ = alice.request("GET", "/api/contents/grades")
            names = [entry["name"] for entry in json.loads(listing)["content"]]
            assert names == ["deadline"], names
            with alice.terminal() as term:
                code, said = term.run("cat ~/grades/deadline/results.json | grep -c bob; touch ~/grades/deadline/x")
            assert code != 0 and "Read-only" in said, said
            for other in ("gradebook.csv", "report.html"):
                assert not (hub.data / "users" / "alice" / "grades" / "deadline" / other).exists(), other
            return "alice reads ~/grades/deadline/report.txt (PASS) in her workbench; read-only; no one else's"
        report.attempt("each student sees their own report, nobody another's", own_report)
    finally:
        for term in terms.values():
            try:
                term.close()
            except Exception:
                pass
        hub.stop()
        cleanup(work, opts.keep)
    return finish(report, started)


def cleanup(work: Path, keep: bool) -> None:
    """The check's containers and networks (the hub stops the servers; this makes sure), its data."""
    for container in podman_out("ps", "-aq", "--filter", "name=course-hub-").split():
        podman_out("rm", "-f", container)
    for network in podman_out("network", "ls", "-q", "--filter", "name=course-hub-net-").split():
        podman_out("network", "rm", "-f", network)
    if not keep:
        shutil.rmtree(work, ignore_errors=True)
    else:
        print("hub check: kept %s" % work)


def finish(report: Report, started: float) -> int:
    print("hub check took %.0f s, load average %s" % (time.monotonic() - started, " ".join(
        open("/proc/loadavg").read().split()[:3])))
    print("hub check %d/%d" % (report.passed, report.total), flush=True)
    return 0 if report.passed == report.total and report.total else 1


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--image", default="localhost/ros-course", help="the student image's tag")
    parser.add_argument("--no-build", action="store_true", help="use the image as it is")
    parser.add_argument("--keep", action="store_true", help="keep the scratch folder (data, logs)")
    opts = parser.parse_args()
    if os.geteuid() != 0:
        print("hub check: run it as root (sudo make hub-check): podman runs the containers as root here",
              file=sys.stderr)
        return 2
    try:
        return run(opts)
    except Exception:
        traceback.print_exc()
        return 1


if __name__ == "__main__":
    sys.exit(main())
