"""`make hub-check`: the class's hub end to end, with real parts (root, podman). An end-to-end suite
(the `e2e` marker: `make test` leaves it out).

    sudo make hub-check                                   # builds the student image, then checks
    sudo make hub-check HUB_CHECK_ARGS="--image localhost/ros-course-hub --no-build"

The student image (docker/Dockerfile's default target), `make hub`'s own start (course-hub of the
hub's venv: the data folder and initial passwords, podman's Docker API on a socket of its own,
JupyterHub with deploy/jupyterhub's config, a class list of a TA and four students, a scratch
data folder), then the students at their
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
- `hub_grade` snapshots the class and grades it: alice's chatter (courses/robotics_labs/samples'
  lab2_chatter_scripts, chmod +x in her terminal) passes, bob's (lab2_chatter_no_chmod) fails
  with its reason, carol (nothing) gets no points; each reads their own report in ~/grades of
  their workbench, read-only, and only their own.

One line per check, the last `hub check K/N`; the test passes when all passed. Everything it
started is stopped and removed at the end (--keep leaves the data folder). HUB_CHECK_ARGS in the
environment holds the options (course_testkit.hub_suite.options):

    sudo HUB_CHECK_ARGS="--no-build" python3 -m pytest -m e2e -s tests/e2e/test_hub.py   # sourced workspace
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import re
import secrets
import shutil
import signal
import subprocess
import time
import urllib.parse
import urllib.request
from pathlib import Path
from typing import Dict, List

import pytest

from course_hub import names as hub_names
from course_hub.runner import PODMAN  # the hub's own podman: its networks
from course_hub import passwords as hub_passwords
from course_testkit.browser import chromium
from course_testkit.hub import HubUser, LocalHub, SpawnFailed
from course_testkit.hub_suite import (CONNECT, EVIL_PAGE, HUB_CHECK, Report, build_image, container_ip, host_connects,
                                      other_host, podman_out, run_as_test, upload)
from course_testkit.jupyter import Terminal
from course_testkit.podman import CHECKOUT
from course_checks.waiting import wait_for

pytestmark = pytest.mark.e2e

STUDENTS = ("alice", "bob", "carol")
# names that once shared folders (DockerSpawner escaped - as -2d, the hooks did not): each must
# save into their own src and be graded on it; a-b also races the snapshot, a-2db hands in a
# sparse file, jean-luc fills their disk
NAMED = ("a-b", "a-2db", "jean-luc")
RACER, SPARSE, FILLER = NAMED
EVIL_PORT = 8765
FAILING = "dave"        # a student whose server cannot start (a memory limit too small)
TA = "tom"
TOO_LITTLE_MEMORY = "8M"  # JupyterLab cannot answer in it (24M sometimes did, then died)
MILESTONE = "chatter"
SAMPLES = CHECKOUT / "courses" / "robotics_labs" / "samples"
FILES = {"alice": SAMPLES / "lab2_chatter_scripts" / "lab2" / "src" / "chatter",
         "bob": SAMPLES / "lab2_chatter_no_chmod" / "chatter"}
# dave's server is given too little memory to start; the others keep the course's limit
CHECK_CONFIG = '''from course_hub import defaults
course_limit = c.CourseSpawner.mem_limit if "mem_limit" in c.CourseSpawner else defaults.MEM_LIMIT
c.CourseSpawner.mem_limit = lambda spawner: %(small)r if spawner.user.name == %(failing)r else course_limit
''' % {"small": TOO_LITTLE_MEMORY, "failing": FAILING}


def run(opts: argparse.Namespace, report: Report, work: Path) -> None:
    """Every check in turn, each a line of `report`; the first whose failure leaves nothing to check ends it."""
    if not opts.no_build:
        report.attempt("image %s built from docker/Dockerfile" % opts.image,
                       lambda: (build_image(opts.image, work / "build.log"), "log in %s" % (work / "build.log"))[1])
    extra = Path(opts.extra_config).read_text() if opts.extra_config else ""
    hub = LocalHub(opts.image, work, STUDENTS + NAMED + (FAILING,), (TA,), CHECK_CONFIG + extra)
    users: Dict[str, HubUser] = {}
    terms: Dict[str, object] = {}
    passwords: Dict[str, str] = {}
    try:
        if not report.attempt("make hub's runner starts JupyterHub with deploy/jupyterhub's config", hub.start):
            print(hub.tail())
            return
        # the initial passwords the hub gave the class list at its start (its hand-out sheet)
        passwords.update(hub_passwords.handed_out(str(hub.data)))
        for name in STUDENTS + NAMED + (TA,):
            users[name] = HubUser(hub.url, name, passwords[name])

        def logins() -> str:
            assert sorted(passwords) == sorted(STUDENTS + NAMED + (FAILING, TA)), sorted(passwords)
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
            return ("%d users on the hand-out sheet; %d log in with theirs; claiming a listed name first, a wrong "
                    "password and a name off the list refused" % (len(passwords), len(users)))
        report.attempt("each user logs in through the hub's form (xsrf, cookies)", logins)

        spawn_times: Dict[str, float] = {}

        def spawns() -> str:
            for name in STUDENTS:
                spawn_times[name] = users[name].start()
                status, url = users[name].open_server()
                assert status == 200 and "/user/%s/lab" % name in url, (name, status, url)
            return ", ".join("%s %.1f s" % kv for kv in spawn_times.items())
        report.attempt("each student starts their server and opens JupyterLab through the hub", spawns)

        def own_origin() -> str:
            origins = {name: users[name].origins.get(name, "") for name in STUDENTS}
            hub_host = urllib.parse.urlparse(hub.url).netloc
            for name, origin in origins.items():
                assert origin == "http://%s.%s" % (name, hub_host), (name, origin)
            return "servers at %s; the hub at %s" % (", ".join(origins.values()), hub.url)
        report.attempt("each student's server has its own origin (subdomain)", own_origin)

        def names_apart() -> str:
            said = []
            for name in NAMED:
                users[name].start()
                status, url = users[name].open_server()
                assert status == 200, (name, status, url)
                users[name].write_file("catkin_ws/src/owner.txt", name)
            for name in NAMED:
                status, data, _ = users[name].request("GET", "/api/contents/catkin_ws/src/owner.txt")
                owner = json.loads(data).get("content") if status == 200 else None
                assert owner == name, "%s reads %r in their own src" % (name, owner)
                host = hub.data / "users" / hub_names.slug(name) / "src" / "owner.txt"
                assert host.read_text() == name, (name, host)
                said.append("%s in users/%s" % (name, hub_names.slug(name)))
            return "each saved into their own src and reads only it: %s" % ", ".join(said)
        report.attempt("a-b, a-2db and jean-luc each save in a folder of their own", names_apart)

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
            return

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

        def hardened() -> str:
            code, said = terms["alice"].run(
                "touch /course/x 2>&1; grep -E '^(NoNewPrivs|CapEff|CapPrm)' /proc/self/status; "
                "echo uid_map $(cat /proc/self/uid_map); "
                "df -h --output=size,target ~/catkin_ws/src /tmp ~ | tail -n +2")
            assert "Read-only file system" in said, said
            assert re.search(r"NoNewPrivs:\s+1", said) and re.search(r"CapEff:\s+0+\b", said), said
            mapped = re.search(r"uid_map (\d+) (\d+) (\d+)", said)
            assert mapped and mapped.group(2) != "0", "no user namespace of its own: %s" % said
            owner = (hub.data / "users" / "alice" / "src").stat().st_uid
            assert owner >= int(mapped.group(2)), "alice's src is host uid %d" % owner
            return " | ".join(line.strip() for line in said.splitlines() if line.strip())
        report.attempt("a student's container: its own user namespace, the course read-only, no new privileges, "
                       "no capabilities", hardened)

        def disk_bound() -> str:
            filler = users[FILLER]
            free_before = shutil.disk_usage(hub.data).free
            with filler.terminal() as term:
                code, src = term.run("head -c 3G /dev/zero > ~/catkin_ws/src/fill; echo exit=$?")
                code, tmp = term.run("head -c 3G /dev/zero > /tmp/fill; echo exit=$?")
                code, home = term.run("du -sh ~/catkin_ws/src/fill /tmp/fill")
            assert "No space left on device" in src and "No space left on device" in tmp, (src, tmp)
            grew = free_before - shutil.disk_usage(hub.data).free
            assert grew < 64 * 2 ** 20, "the host's disk lost %d MiB" % (grew // 2 ** 20)
            filler.stop()
            assert wait_for(lambda: not filler.server_state(), 120, 1.0), "a-2db's server did not stop"
            seconds = filler.start()  # a full disk: the workbench still starts
            status, url = filler.open_server()
            assert status == 200, (status, url)
            with filler.terminal() as term:
                term.run("rm -f ~/catkin_ws/src/fill")
            return ("%s: No space left on device in catkin_ws/src and /tmp (%s); the host's disk lost %d MiB; "
                    "the workbench started again with the disk full in %.1f s" % (
                        FILLER, " ".join(home.split()), grew // 2 ** 20, seconds))
        report.attempt("a student's disk is bounded by the kernel; the workbench still starts at the limit", disk_bound)

        def no_way_to_bob() -> str:
            alice = users["alice"]
            status, url = alice.open_server("bob")
            assert status in (403, 404) or "/user/bob/" not in url, ("lab", status, url)
            as_bob = alice.as_session("bob")
            rest = as_bob.request("GET", "/api/contents/")[0]
            term = as_bob.request("POST", "/api/terminals")[0]
            assert rest >= 400 and term >= 400, ("REST", rest, "terminals", term)
            # and at bob's own origin, straight
            bob_origin = users["bob"].origins["bob"]
            direct = alice.http("GET", bob_origin + "/user/bob/api/contents/")
            assert direct[0] >= 400 or "/user/bob/api" not in direct[2], ("bob's origin", direct[0], direct[2])
            try:
                Terminal(as_bob, "1").close()
            except Exception:
                pass
            else:
                raise AssertionError("alice opened bob's terminal websocket")
            return "bob's lab %d, REST %d, new terminal %d, terminal websocket refused; at %s: %d" % (
                status, rest, term, bob_origin, direct[0])
        report.attempt("alice cannot reach bob's server or terminals through the hub", no_way_to_bob)

        def no_port_of_bob() -> str:
            ip = container_ip(PODMAN, "bob")
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

        def hostile_page() -> str:
            alice = users["alice"]
            alice.make_folder("www")
            alice.write_file("www/evil.html", EVIL_PAGE % {"hub": hub.url})
            code, said = terms["alice"].run("(cd ~/www && python3 -m http.server %d --bind 127.0.0.1 > /dev/null 2>&1 &)"
                                            % EVIL_PORT)
            tom = users[TA]
            status, tokens_before = tom.hub_api("GET", "/users/%s/tokens" % TA)
            with chromium(arguments=("--disable-popup-blocking",)) as browser:  # a TA's browser allows the hub's popups
                browser.get(hub.url + "/hub/login")
                browser.find_element("name", "username").send_keys(TA)
                browser.find_element("name", "password").send_keys(passwords[TA])
                browser.find_element("id", "login_submit").click()
                assert wait_for(lambda: "/hub/login" not in browser.current_url, 30, 0.2), browser.current_url
                browser.get(hub.url + "/user/alice/lab")  # the TA opens alice's server to help her
                if "/oauth2/authorize" in browser.current_url:
                    browser.find_element("css selector", "form input[type=submit], form button").click()
                assert wait_for(lambda: "/user/alice/" in browser.current_url, 60, 0.2), browser.current_url
                where = urllib.parse.urlparse(browser.current_url)
                page = "%s://%s/user/alice/proxy/%d/evil.html" % (where.scheme, where.netloc, EVIL_PORT)
                browser.get(page)
                assert wait_for(lambda: browser.title.startswith("done"), 60, 0.5), browser.page_source[:500]
                seen = browser.title
            status, alice_model = tom.hub_api("GET", "/users/alice")
            assert status == 200 and not alice_model.get("admin"), ("alice became admin", seen)
            status, tokens_after = tom.hub_api("GET", "/users/%s/tokens" % TA)

            def own_tokens(model: Dict) -> List[str]:  # not the OAuth tokens opening servers makes
                return [t["id"] for t in (model or {}).get("api_tokens", []) if not t.get("oauth_client")]
            made = set(own_tokens(tokens_after)) - set(own_tokens(tokens_before))
            assert not made, ("a token was made for tom", seen, made)
            assert "popup-not-opened" not in seen, "the browser blocked the popup: nothing was tried (%s)" % seen
            for word in ("read:200", "patch:200", "popup-read", "xsrf-patch:", "token:"):
                assert word not in seen, seen
            return "alice's page at %s, opened by the TA: %s; alice is no admin, tom has no new token" % (
                page.split("/user/")[0], seen[5:])
        report.attempt("a page alice serves, opened by a TA, cannot act on the hub", hostile_page)

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
            with users[SPARSE].terminal() as term:  # costs jean-luc nothing: a hole of 16 GiB
                code, said = term.run("truncate -s 16G ~/catkin_ws/src/big.bin && du -h --apparent-size ~/catkin_ws/src/big.bin")
            assert code == 0, said
            return "uploaded %s; alice did chmod +x; %s made a sparse file of %s" % (counts, SPARSE, said.split()[0])
        report.attempt("alice and bob write their chatter package in the workbench", files)

        for term in terms.values():
            term.close()
        terms.clear()

        def culled() -> str:
            culler = subprocess.Popen(
                [str(CHECKOUT / ".venv-hub" / "bin" / "python3"), "-m", "jupyterhub_idle_culler", "--timeout=1",
                 "--cull-every=2", "--url=%s/hub/api" % hub.url],
                env=dict(os.environ, JUPYTERHUB_API_TOKEN=hub.culler_token), stdout=subprocess.DEVNULL,
                stderr=subprocess.STDOUT, start_new_session=True)
            try:
                gone = wait_for(lambda: not any(users[n].server_state() for n in STUDENTS + NAMED), 120, 1.0)
            finally:
                os.killpg(culler.pid, signal.SIGTERM)
                culler.wait(30)
            assert gone, "still running: %s" % [n for n in STUDENTS + NAMED if users[n].server_state()]
            assert not podman_out(PODMAN, "ps", "-q", "--filter", "name=course-hub-alice"), "alice's container is still there"
            seconds = users["alice"].start()
            status, url = users["alice"].open_server()  # a new server: the hub's OAuth again
            assert status == 200 and "/user/alice/lab" in url, (status, url)
            status, data, _ = users["alice"].request("GET", "/api/contents/catkin_ws/src/chatter/package.xml")
            assert status == 200 and b"chatter" in data, (status, data[:300])
            with users["alice"].terminal() as term:
                code, said = term.run("test -x ~/catkin_ws/src/chatter/scripts/talker_node.py && pgrep -f turtlesim_node")
            assert code != 0, "after the cull: %s" % said
            return ("all %d culled (containers removed); alice back in %.1f s with her files, a fresh container"
                    % (len(STUDENTS + NAMED), seconds))
        report.attempt("the idle culler stops idle servers; alice's files survive", culled)

        grades: Dict[str, Dict] = {}

        def grading() -> str:
            # a-b's terminal swaps a folder of her src with a link to the hub's data folder, in a
            # tight loop, while root snapshots the class
            racer = users[RACER]
            racer.start()
            racer.open_server()
            race = racer.terminal()
            # 400 files in the folder she swaps: the copy takes long enough for the loop to hit it
            race.run("mkdir -p ~/catkin_ws/src/pkg && cd ~/catkin_ws/src && for i in $(seq 400); do echo $i > pkg/f$i; "
                     "done && (timeout 600 bash -c 'n=0; while true; do "
                     "ln -sfn %s pkg.link; mv -T pkg pkg.real; mv -T pkg.link pkg; mv -T pkg pkg.link; "
                     "mv -T pkg.real pkg; n=$((n+1)); echo $n > /tmp/swaps; done' > /dev/null 2>&1 &)" % hub.data)
            assert wait_for(lambda: race.run("cat /tmp/swaps 2>/dev/null")[1].strip().isdigit(), 30, 0.2), \
                "a-b's swapping loop does not run"
            try:
                done = subprocess.run(["rosrun", "course_hub", "hub_grade", "--data", str(hub.data), "--class-list",
                                       str(hub.class_list), "--only", MILESTONE, "--stamp", "deadline"],
                                      stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
            finally:
                swaps = race.run("pkill -f pkg.link; cat /tmp/swaps")[1].strip()
                race.close()
            book = hub.data / "grades" / "deadline" / "gradebook.csv"
            assert book.is_file(), done.stdout[-2000:]
            with open(book) as rows:
                for row in csv.DictReader(rows):
                    grades[row.get("student") or next(iter(row.values()))] = row
            assert set(STUDENTS + NAMED) <= set(grades), "gradebook rows: %s" % sorted(grades)
            snap = hub.data / "snapshots" / "deadline" / "alice" / "chatter" / "package.xml"
            assert snap.is_file() and not os.access(snap, os.W_OK) or os.geteuid() == 0 and not snap.stat().st_mode & 0o222, \
                "the snapshot is writable"
            secrets_of_host = [p.read_bytes() for p in (hub.data / "jupyterhub_cookie_secret",
                                                        hub.data / "initial-passwords.csv") if p.is_file()]
            leaked = [str(p) for top in (hub.data / "snapshots", hub.data / "grades") for p in top.rglob("*")
                      if p.is_file() and not p.is_symlink() and p.stat().st_size < 2 ** 20
                      and any(secret and secret in p.read_bytes() for secret in secrets_of_host)]
            assert not leaked, "host files in the snapshot or the grading: %s" % leaked
            raced = "graded" if (hub.data / "snapshots" / "deadline" / RACER).is_dir() else "not graded"
            return ("gradebook rows %s; %s swapped a folder for a link to the hub's data %s times while the snapshot "
                    "ran: %s, no host file in any snapshot or output (exit %d)" % (
                        sorted(grades), RACER, swaps, raced, done.returncode))
        report.attempt("hub_grade snapshots the class read-only and grades it, keyed by hub user", grading)

        def named_and_bounded() -> str:
            not_graded = {}
            listing = hub.data / "grades" / "deadline" / "not-graded.csv"
            if listing.is_file():
                with open(listing) as rows:
                    not_graded = {row["student"]: row["reason"] for row in csv.DictReader(rows)}
            assert "more than 200 MB" in not_graded.get(SPARSE, ""), not_graded
            report_txt = hub.data / "users" / hub_names.slug(SPARSE) / "grades" / "deadline" / "report.txt"
            assert "Not graded" in report_txt.read_text(), report_txt
            snaps = hub.data / "snapshots" / "deadline"
            used = sum(p.lstat().st_blocks * 512 for top in (snaps, hub.data / "grades") for p in top.rglob("*"))
            assert used < 256 * 2 ** 20, "snapshots and gradings take %d MiB" % (used // 2 ** 20)
            owner = (snaps / FILLER / "owner.txt").read_text()
            assert owner == FILLER, "%s's snapshot holds %r's owner.txt" % (FILLER, owner)
            if RACER in not_graded:
                assert "changed while it was copied" in not_graded[RACER], not_graded[RACER]
            else:
                assert (snaps / RACER / "owner.txt").read_text() == RACER
            return "%s not graded (%s); %s graded on their own files; snapshots and gradings use %d MiB" % (
                SPARSE, not_graded[SPARSE][:60], FILLER, used // 2 ** 20)
        report.attempt("each named student graded on their own work; a sparse file refused with its reason",
                       named_and_bounded)

        def old_gradings_closed() -> str:
            tried = []
            for path in (hub.data / "snapshots" / "deadline" / "alice" / "chatter" / "package.xml",
                         hub.data / "users" / "bob" / "src" / "chatter" / "package.xml",
                         hub.data / "grades" / "deadline" / "alice" / "results.json",
                         hub.data / "initial-passwords.csv"):
                done = subprocess.run(["runuser", "-u", "coursesandbox", "--", "cat", str(path)],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                assert done.returncode != 0 and "Permission denied" in done.stderr, (path, done.stderr)
                tried.append(str(path.relative_to(hub.data)))
            return "the grader's sandbox user is refused %s" % ", ".join(tried)
        report.attempt("a later grading's student code reads no snapshot, grading or student folder",
                       old_gradings_closed)

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

        def login_flood() -> str:
            import threading
            slowest = [0.0]
            stop = threading.Event()

            def probe() -> None:
                while not stop.is_set():
                    began = time.monotonic()
                    urllib.request.urlopen(hub.url + "/hub/api/", timeout=30).read()
                    slowest[0] = max(slowest[0], time.monotonic() - began)
                    time.sleep(0.05)

            def wrong(i: int) -> None:
                try:
                    HubUser(hub.url, TA, "wrong-%d" % i).login()
                except Exception:
                    pass
            prober = threading.Thread(target=probe)
            prober.start()
            tries = []
            began = time.monotonic()
            for i in range(20):  # 20 wrong logins in 2 s
                tries.append(threading.Thread(target=wrong, args=(i,)))
                tries[-1].start()
                time.sleep(0.1)
            for thread in tries:
                thread.join()
            flood = time.monotonic() - began
            time.sleep(0.5)
            stop.set()
            prober.join()
            assert slowest[0] < 1.0, "/hub/api/ took %.2f s during the wrong logins" % slowest[0]
            try:
                HubUser(hub.url, TA, passwords[TA]).login()
            except Exception as err:
                refused = str(err)
            else:
                raise AssertionError("tom's right password let in right after 20 wrong ones")
            assert "Too many failed logins" in refused, refused
            status, _ = users[TA].hub_api("GET", "/users/%s" % TA)
            assert status == 200, "tom's own session ended: %d" % status
            return ("20 wrong logins in %.1f s: /hub/api/ answered within %.2f s at worst; then the right password "
                    "refused: %s; tom's open session unaffected" % (flood, slowest[0], refused[-70:]))
        report.attempt("wrong logins neither stall the hub nor go on unlimited", login_flood)

        def removed_from_list() -> str:
            hub.stop()
            with open(hub.class_list) as rows:
                kept = [line for line in rows if not line.startswith("bob,")]
            hub.class_list.write_text("".join(kept))
            hub.start()
            try:
                HubUser(hub.url, "bob", passwords["bob"]).login()
            except Exception as err:
                bob = str(err)
            else:
                raise AssertionError("bob, taken off the class list, still logs in")
            HubUser(hub.url, "alice", passwords["alice"]).login()
            return "the hub started again without bob on its list: bob refused (%s); alice logs in" % bob[-60:]
        report.attempt("a student taken off the class list can no longer log in", removed_from_list)

        def api_port_closed() -> str:
            listening = subprocess.run(["ss", "-Hltn", "sport = :%d" % hub.api_port], stdout=subprocess.PIPE,
                                       text=True, check=False).stdout
            assert "0.0.0.0:%d" % hub.api_port in listening, "the hub's API: %r" % listening
            with other_host() as (host_ip, run_there):
                other = subprocess.Popen(["python3", "-m", "http.server", str(EVIL_PORT), "--bind", "0.0.0.0"],
                                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                try:
                    assert wait_for(lambda: run_there(CONNECT % (host_ip, EVIL_PORT)) == 0, 20, 0.3), \
                        "the test host reaches no port of this machine"
                    reached = run_there(CONNECT % (host_ip, hub.api_port)) == 0
                finally:
                    other.terminate()
                    other.wait()
            assert not reached, "a host on the network reached the hub's API port %d" % hub.api_port
            # and the containers still call it (their servers started and answer: the checks above)
            return ("JupyterHub listens on 0.0.0.0:%d; a host on the network (a namespace of this check, at %s) "
                    "reaches another port listening on every address, not the hub's API" % (hub.api_port, host_ip))
        report.attempt("the hub's API port is closed to the network, open to the containers", api_port_closed)
    finally:
        for term in terms.values():
            try:
                term.close()
            except Exception:
                pass
        hub.stop()


def test_the_hub_end_to_end():
    run_as_test(HUB_CHECK, run, PODMAN)
