"""The class's hub end to end (tests/e2e/test_hub.py, `make hub-check`; tests/e2e/test_lti.py,
`make lti-check`): what their checks share.

- `run_as_test`: a suite as one pytest test: root only, its options from its make variable, a
  scratch folder, its checks' lines, everything it started removed, the test failed when a check
  failed;

- `Report`: one line per check (`ok  ...` or `FAIL ...: why`), and the count at the end
  (`finish`: `hub check K/N`);
- `build_image`: the student image from docker/Dockerfile (course_testkit.podman's base);
- `other_host`: another host on the network, a network namespace joined to this machine by a veth
  pair, to knock on the hub's ports from outside;
- `upload`: a folder written through the contents API, as the file browser uploads it;
- `cleanup`: the suite's containers, networks, mounts and data removed;
- `EVIL_PAGE`: a page a student serves from her own server, which tries to act on the hub with
  the cookies of whoever opens it;
- `options`: HUB_CHECK_ARGS' (LTI_CHECK_ARGS') words;
- `browser_user`: a user logged in in a browser (an LTI launch) as a HubUser, to use their server
  over HTTP (files, terminals) as test_hub's users do.

Root only, as `make hub`. The hub's own podman command (course_hub.runner.PODMAN: its networks) is
the caller's to give.
"""
from __future__ import annotations

import argparse
import contextlib
import http.cookiejar
import os
import shlex
import shutil
import socket
import subprocess
import tempfile
import time
import urllib.parse
from pathlib import Path
from typing import Any, Callable, Iterator, List, NamedTuple, Sequence, Tuple

import pytest

from course_testkit.hub import HubUser
from course_testkit.podman import PODMAN as BUILD_PODMAN, ensure_podman, import_base, network_mounts
from course_testkit.podman import CHECKOUT, DOCKERFILE


class Suite(NamedTuple):
    """An end-to-end hub suite: its name in its lines ("hub check"), its make target, the
    environment variable holding its options."""

    name: str
    target: str
    variable: str


HUB_CHECK = Suite("hub check", "hub-check", "HUB_CHECK_ARGS")
LTI_CHECK = Suite("lti check", "lti-check", "LTI_CHECK_ARGS")


def options(words: str, suite: Suite = HUB_CHECK) -> argparse.Namespace:
    """The suite's options (`make hub-check HUB_CHECK_ARGS="--image localhost/ros-course-hub --no-build"`)."""
    parser = argparse.ArgumentParser(prog="make %s %s=" % (suite.target, suite.variable))
    parser.add_argument("--image", default="localhost/ros-course", help="the student image's tag")
    parser.add_argument("--no-build", action="store_true", help="use the image as it is")
    parser.add_argument("--keep", action="store_true", help="keep the scratch folder (data, logs)")
    parser.add_argument("--extra-config", default="", help="JupyterHub config run after the course's: to see a "
                        "check fail when a protection is taken away (docs/hub.md)")
    return parser.parse_args(shlex.split(words))


# A page a student serves from her own server (any file behind jupyter-server-proxy's /proxy/<port>/):
# it tries, with the cookies of whoever opens it, to read the hub's API, to make alice an admin
# (which the hub refuses without an XSRF token), then to read a hub page's XSRF token in a popup
# and, with it, to make alice an admin and make a token. Its findings go to its title. On the
# hub's own origin (no subdomains) the popup route works (docs/hub.md, the control).
EVIL_PAGE = """<!doctype html><title>waiting</title><script>
(async () => {
  const hub = "%(hub)s", out = [];
  try { const r = await fetch(hub + "/hub/api/users", {credentials: "include"});
        out.push("read:" + r.status); } catch (e) { out.push("read-blocked"); }
  try { const r = await fetch(hub + "/hub/api/users/alice", {method: "PATCH", credentials: "include",
          headers: {"Content-Type": "application/json"}, body: JSON.stringify({admin: true})});
        out.push("patch:" + r.status); } catch (e) { out.push("patch-blocked"); }
  try { await fetch(hub + "/hub/api/users/alice", {method: "PATCH", mode: "no-cors", credentials: "include",
          body: JSON.stringify({admin: true})}); out.push("blind-patch-sent"); } catch (e) { out.push("blind-blocked"); }
  try { const w = window.open(hub + "/hub/token");
        if (!w) { out.push("popup-not-opened"); throw 0; }
        let xsrf = null;
        for (let i = 0; i < 100 && !xsrf; i++) {
          await new Promise(r => setTimeout(r, 100));
          xsrf = w.jhdata && w.jhdata.xsrf_token;  // a SecurityError unless the hub is this page's origin
        }
        out.push("popup-read");
        const headers = {"X-XSRFToken": xsrf, "Content-Type": "application/json"};
        let r = await fetch(hub + "/hub/api/users/alice", {method: "PATCH", credentials: "include", headers,
          body: JSON.stringify({admin: true})});
        out.push("xsrf-patch:" + r.status);
        r = await fetch(hub + "/hub/api/users/tom/tokens", {method: "POST", credentials: "include", headers,
          body: JSON.stringify({note: "alice's"})});
        out.push("token:" + r.status); } catch (e) { if (e !== 0) out.push("popup-blocked"); }
  document.title = "done " + out.join(" ");
})();
</script>"""


class Report:
    """One line per check; the count at the end."""

    def __init__(self) -> None:
        self.passed = 0
        self.total = 0
        self.failed: List[str] = []

    def check(self, name: str, ok: bool, detail: str = "") -> bool:
        self.total += 1
        self.passed += bool(ok)
        if not ok:
            self.failed.append(name)
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
    """The student image, from debian:bookworm imported from a debootstrap when missing (no
    registry is reachable here; course_testkit.podman)."""
    ensure_podman()
    import_base(log)
    scratch = Path(tempfile.mkdtemp(prefix="hub-check-build-"))
    try:
        with open(log, "ab") as out:
            subprocess.run(["nice", "-n", "10"] + BUILD_PODMAN + ["build", "--network", "host", *network_mounts(scratch),
                           "-f", str(DOCKERFILE), "-t", image, str(CHECKOUT)],
                           check=True, stdout=out, stderr=subprocess.STDOUT)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def podman_out(podman: Sequence[str], *args: str) -> str:
    return subprocess.run(list(podman) + list(args), check=False, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                          text=True).stdout.strip()


def container_ip(podman: Sequence[str], user: str) -> str:
    return podman_out(podman, "inspect", "course-hub-%s" % user,
                      "-f", "{{range .NetworkSettings.Networks}}{{.IPAddress}}{{end}}")


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


@contextlib.contextmanager
def other_host() -> Iterator[Tuple[str, Callable[[str], int]]]:
    """Another host on the network: a network namespace of this check joined to this machine by a
    veth pair (10.250.47.1 here, .2 there); yields this machine's address there and a function
    running a shell command there (its exit code)."""
    name, here, there = "hubcheck-%d" % os.getpid(), "hcv%d" % (os.getpid() % 100000), "hcp%d" % (os.getpid() % 100000)
    setup = [["ip", "netns", "add", name], ["ip", "link", "add", here, "type", "veth", "peer", "name", there],
             ["ip", "link", "set", there, "netns", name], ["ip", "addr", "add", "10.250.47.1/30", "dev", here],
             ["ip", "link", "set", here, "up"],
             ["ip", "netns", "exec", name, "ip", "addr", "add", "10.250.47.2/30", "dev", there],
             ["ip", "netns", "exec", name, "ip", "link", "set", there, "up"],
             ["ip", "netns", "exec", name, "ip", "link", "set", "lo", "up"]]
    try:
        for command in setup:
            subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        yield "10.250.47.1", lambda shell: subprocess.run(["ip", "netns", "exec", name, "sh", "-c", shell],
                                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    finally:
        subprocess.run(["ip", "link", "del", here], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        subprocess.run(["ip", "netns", "del", name], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def cleanup(podman: Sequence[str], work: Path, keep: bool) -> None:
    """The check's containers and networks (the hub stops the servers; this makes sure), the
    students' disks unmounted (LocalHub.stop does; this makes sure), its data."""
    for container in podman_out(podman, "ps", "-aq", "--filter", "name=course-hub-").split():
        podman_out(podman, "rm", "-f", container)
    for network in podman_out(podman, "network", "ls", "-q", "--filter", "name=course-hub-net-").split():
        podman_out(podman, "network", "rm", "-f", network)
    with open("/proc/mounts") as mounts:
        mounted = [line.split()[1] for line in mounts if line.split()[1].startswith(str(work) + "/")]
    for point in sorted(mounted, reverse=True):
        subprocess.run(["umount", point], check=False)
    if not keep:
        shutil.rmtree(work, ignore_errors=True)
    else:
        print("hub check: kept %s" % work)


def finish(report: Report, started: float, name: str = HUB_CHECK.name) -> int:
    """The suite's last lines: its time and the machine's load, then `<name> K/N`; 0 when all passed."""
    print("%s took %.0f s, load average %s" % (name, time.monotonic() - started, " ".join(
        open("/proc/loadavg").read().split()[:3])))
    print("%s %d/%d" % (name, report.passed, report.total), flush=True)
    return 0 if report.passed == report.total and report.total else 1


def run_as_test(suite: Suite, run: Callable[[argparse.Namespace, Report, Path], None], podman: Sequence[str]) -> None:
    """`run(options, report, scratch folder)` as a pytest test: as root only (podman runs the
    containers as root here), a scratch folder of its own (the hub's data, logs), then the
    containers, networks, mounts and folder removed however it ended (`cleanup`, with the hub's
    `podman`); the test fails naming the checks that failed, or when none ran."""
    opts = options(os.environ.get(suite.variable, ""), suite)
    if os.geteuid() != 0:
        pytest.fail("run it as root (sudo make %s): podman runs the containers as root here" % suite.target,
                    pytrace=False)
    report = Report()
    work = Path(tempfile.mkdtemp(prefix="%s-" % suite.target))
    os.chmod(work, 0o755)
    started = time.monotonic()
    try:
        run(opts, report, work)
    finally:
        cleanup(podman, work, opts.keep)
        finish(report, started, suite.name)
    if report.failed or not report.total:
        pytest.fail("%s: %d of %d checks failed (their lines above say why): %s" % (
            suite.name, len(report.failed), report.total, "; ".join(report.failed)), pytrace=False)


def browser_user(driver: Any, hub_url: str, name: str) -> HubUser:
    """User `name`, logged in to the hub in the browser `driver` (a selenium driver) and now on a
    page of their own server: a HubUser holding that server's cookies (its OAuth login, _xsrf),
    which speaks to the server over HTTP (REST, terminals) as the browser would. Only what the
    server's origin holds: the hub's own API needs the hub's cookies."""
    user = HubUser(hub_url, name, "")
    where = urllib.parse.urlsplit(driver.current_url)
    assert where.path.startswith("/user/%s/" % name), driver.current_url
    user.origins[name] = "%s://%s" % (where.scheme, where.netloc)
    for cookie in driver.get_cookies():
        domain = cookie.get("domain") or where.hostname or ""
        user.jar.set_cookie(http.cookiejar.Cookie(
            0, cookie["name"], cookie["value"], None, False, domain, domain.startswith("."), domain.startswith("."),
            cookie.get("path") or "/", True, bool(cookie.get("secure")), cookie.get("expiry"), False, None, None, {}))
    return user
