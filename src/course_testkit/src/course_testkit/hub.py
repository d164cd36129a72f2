"""A JupyterHub user for tests and benchmarks, driven over HTTP as a browser drives the hub.

`HubUser(hub_url, name, password)`:

- `login()`: GET /hub/login (the `_xsrf` cookie and the form's hidden field), then POST the form
  (username, password, _xsrf); the hub's login cookie lands in the user's own cookie jar.
- `start()`: POST /hub/api/users/<name>/server (as the hub's home page's Start button does: the
  login cookie and the X-XSRFToken header), then the spawn's progress events
  (/hub/api/users/<name>/server/progress, the event stream the spawn-pending page reads) to their
  end: ready, or failed with the hub's message (`SpawnFailed`).
- `open_server(owner)`: GET /user/<owner>/lab, following the redirects of the hub's OAuth (the
  server's own login cookie then set): (status, final URL). A user may open another's server
  only as an admin.
- Then a `JupyterSession` on `/user/<owner>/`: the REST API, files, and terminals
  (course_testkit.jupyter.Terminal) through the hub's proxy with the cookies alone, no token.

`LocalHub(image, work, students, tas, extra_config)` is `make hub`'s own start (`course-hub` of
the hub's venv, deploy/jupyterhub's config) on a scratch data folder and class list, on free ports, its
own podman socket, and no managed culler (the caller runs jupyterhub-idle-culler with
`culler_token` when it wants servers culled); `extra_config` is config text run after the
course's; `env`, more of make's variables (`HUB_AUTH=lti` and its `HUB_LTI_*`: the login from the
LMS). Root only, as `make hub`.
"""
from __future__ import annotations

import csv
import http.cookiejar
import json
import os
import re
import secrets
import signal
import subprocess
import time
import urllib.error
import urllib.parse
import urllib.request
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

from tornado.httpclient import HTTPRequest

from course_checks import isolation
from course_checks.waiting import wait_for
from course_testkit.jupyter import JupyterError, JupyterSession

REQUEST_TIMEOUT_S = 30.0
SPAWN_TIMEOUT_S = 300.0
HUB_START_TIMEOUT_S = 240.0
HUB_STOP_TIMEOUT_S = 180.0
CHECKOUT = Path(__file__).resolve().parents[4]  # <checkout>/src/course_testkit/src/course_testkit/hub.py
LOCAL_CONFIG = '''# LocalHub's additions to the course's config (course_testkit.hub)
c = get_config()  # noqa: F821
load_subconfig(%(course)r)  # noqa: F821
c.ConfigurableHTTPProxy.api_url = "http://127.0.0.1:%(proxy_api_port)d"
c.JupyterHub.services = [{"name": "idle-culler", "api_token": %(culler_token)r}]
'''


class SpawnFailed(JupyterError):
    """The hub reported that the server did not start; the message is the hub's."""


class HubUser(JupyterSession):
    """One person at a browser: their own cookies (see the module docstring). As a session it
    speaks to the server of `server_owner` (default: their own)."""

    def __init__(self, hub_url: str, name: str, password: str) -> None:
        self.hub_url = hub_url.rstrip("/")
        self.name, self.password = name, password
        self.server_owner = name
        self.jar = http.cookiejar.CookieJar()
        self.opener = urllib.request.build_opener(urllib.request.HTTPCookieProcessor(self.jar))
        self.last_progress: List[Dict[str, Any]] = []
        # where each server lives: its own host under JupyterHub's subdomain_host, learnt from the
        # hub's redirect when it is opened (open_server); the hub's own address until then
        self.origins: Dict[str, str] = {}

    # --- the browser's plumbing ---------------------------------------------------------------

    def _sent_to(self, cookie: http.cookiejar.Cookie, url: str) -> bool:
        parts = urllib.parse.urlparse(url)
        host = parts.hostname or ""
        # a host-only cookie of a name without a dot is kept under <name>.local (RFC 2965's rule)
        return cookie.domain.lstrip(".") in (host, host + ".local") and \
            parts.path.startswith(cookie.path.rstrip("/") or "/")

    def cookie(self, name: str, url: str) -> Optional[str]:
        """The value of cookie `name` that a browser sends to `url` (the longest path first)."""
        found = [c for c in self.jar if c.name == name and self._sent_to(c, url)]
        found.sort(key=lambda c: len(c.path), reverse=True)
        return found[0].value if found else None

    def cookie_header(self, url: str) -> str:
        return "; ".join("%s=%s" % (c.name, c.value) for c in self.jar if self._sent_to(c, url))

    def url(self, path: str) -> str:
        """A path on the hub's address; a full URL stays as it is."""
        return path if path.startswith(("http://", "https://")) else self.hub_url + path

    def http(self, method: str, path: str, data: Optional[bytes] = None, headers: Optional[Dict[str, str]] = None,
             timeout: float = REQUEST_TIMEOUT_S) -> Tuple[int, bytes, str]:
        """(status, body, final URL) of a request to the hub's `path` (or a full URL), redirects
        followed, cookies kept."""
        headers = dict(headers or {})
        xsrf = self.cookie("_xsrf", self.url(path).split("?")[0])
        if xsrf and method != "GET":
            headers.setdefault("X-XSRFToken", xsrf)
        request = urllib.request.Request(self.url(path), data=data, method=method, headers=headers)
        try:
            with self.opener.open(request, timeout=timeout) as reply:
                return reply.status, reply.read(), reply.geturl()
        except urllib.error.HTTPError as err:
            return err.code, err.read(), err.geturl()

    # --- the hub -------------------------------------------------------------------------------

    def login(self) -> None:
        status, page, _ = self.http("GET", "/hub/login")
        if status != 200:
            raise JupyterError("GET /hub/login -> %d" % status)
        field = re.search(rb'name="_xsrf"\s+value="([^"]+)"', page)
        xsrf = field.group(1).decode() if field else (self.cookie("_xsrf", self.url("/hub/")) or "")
        form = urllib.parse.urlencode({"username": self.name, "password": self.password, "_xsrf": xsrf}).encode()
        # as a browser that opened the hub's home page: the login leads back there (a plain
        # /hub/login leads to /hub/spawn, which starts the server: start() does that here)
        status, page, url = self.http("POST", "/hub/login?next=%2Fhub%2Fhome", form,
                                      {"Content-Type": "application/x-www-form-urlencoded"})
        if status >= 400 or urllib.parse.urlparse(url).path.rstrip("/") == "/hub/login":
            raise JupyterError("login of %s refused (%d): %s" % (self.name, status, _text(page)))

    def hub_api(self, method: str, path: str, body: Any = None) -> Tuple[int, Any]:
        """(status, JSON or text) of /hub/api<path> with the login cookie and the XSRF header."""
        xsrf = self.cookie("_xsrf", self.url("/hub/")) or ""
        headers = {"X-XSRFToken": xsrf}
        data = None
        if body is not None:
            data, headers["Content-Type"] = json.dumps(body).encode(), "application/json"
        status, raw, _ = self.http(method, "/hub/api" + path, data, headers)
        try:
            return status, json.loads(raw) if raw else None
        except ValueError:
            return status, _text(raw)

    def server_state(self) -> Dict[str, Any]:
        """The hub's model of the user's default server ({} when it is not running)."""
        status, model = self.hub_api("GET", "/users/%s" % self.name)
        if status != 200:
            raise JupyterError("GET /hub/api/users/%s -> %d: %s" % (self.name, status, model))
        return (model.get("servers") or {}).get("", {})

    def start(self, timeout: float = SPAWN_TIMEOUT_S) -> float:
        """Start the user's server and wait for the spawn's end; seconds it took. SpawnFailed
        with the hub's message when it failed."""
        began = time.monotonic()
        # as a browser clicks Start on the home page it just loaded: that page's XSRF cookie (a
        # request elsewhere, e.g. to another's /user/ path on the hub, may have replaced it)
        self.http("GET", "/hub/home")
        status, answer = self.hub_api("POST", "/users/%s/server" % self.name)
        # 400: already running; 500: the spawn failed at once (its reason is in the progress
        # events, which the hub's spawn page shows)
        if status not in (201, 202, 400, 500):
            raise JupyterError("starting %s's server -> %d: %s" % (self.name, status, answer))
        self.last_progress = self.progress(timeout)
        final = self.last_progress[-1] if self.last_progress else {}
        if final.get("failed") or not final.get("ready"):
            raise SpawnFailed(final.get("message") or "no end of the spawn's progress: %s" % self.last_progress)
        return time.monotonic() - began

    def progress(self, timeout: float) -> List[Dict[str, Any]]:
        """The spawn's progress events (server-sent events) up to the last."""
        xsrf = self.cookie("_xsrf", self.url("/hub/")) or ""
        request = urllib.request.Request(self.hub_url + "/hub/api/users/%s/server/progress" % self.name,
                                         headers={"Accept": "text/event-stream", "X-XSRFToken": xsrf})
        events: List[Dict[str, Any]] = []
        try:
            with self.opener.open(request, timeout=timeout) as stream:
                for line in stream:
                    if line.startswith(b"data:"):
                        events.append(json.loads(line[5:]))
                        if events[-1].get("ready") or events[-1].get("failed"):
                            break
        except urllib.error.HTTPError as err:
            raise JupyterError("progress of %s's spawn -> %d: %s" % (self.name, err.code, _text(err.read())))
        return events

    def stop(self) -> None:
        self.hub_api("DELETE", "/users/%s/server" % self.name)

    def open_server(self, owner: Optional[str] = None) -> Tuple[int, str]:
        """GET /user/<owner>/lab as a browser: (status, final URL) after the hub's OAuth redirects.
        Opening another's server (an admin), the hub first asks to authorize the access: the form
        is sent as its Authorize button sends it."""
        owner = owner or self.name
        status, page, url = self.http("GET", "/user/%s/lab" % owner)
        parsed = urllib.parse.urlparse(url)
        if status == 200 and parsed.path == "/hub/api/oauth2/authorize" and b'<form method="post"' in page:
            fields = re.findall(rb'<input type="hidden" name="([^"]+)" value="([^"]*)"', page)
            form = urllib.parse.urlencode([(k.decode(), v.decode()) for k, v in fields]).encode()
            status, page, url = self.http("POST", "%s://%s%s?%s" % (parsed.scheme, parsed.netloc, parsed.path,
                                                                    parsed.query), form,
                                          {"Content-Type": "application/x-www-form-urlencoded"})
        parsed = urllib.parse.urlparse(url)
        if status == 200 and parsed.path.startswith("/user/%s/" % owner):
            self.origins[owner] = "%s://%s" % (parsed.scheme, parsed.netloc)
        return status, url

    def as_session(self, owner: str) -> "HubUser":
        """This user, speaking to `owner`'s server (a TA helping a student)."""
        other = HubUser(self.hub_url, self.name, self.password)
        other.jar, other.opener, other.server_owner, other.origins = self.jar, self.opener, owner, self.origins
        return other

    # --- JupyterSession: the server behind the hub ---------------------------------------------

    def prefix(self) -> str:
        return "/user/%s" % self.server_owner

    def server_origin(self) -> str:
        """scheme://host[:port] of the server spoken to: its own host under subdomains."""
        return self.origins.get(self.server_owner, self.hub_url)

    def request(self, method: str, path: str, body: Any = None, token: Optional[str] = "",
                follow: bool = True) -> Tuple[int, bytes, Dict[str, str]]:
        data, headers = None, {}
        if body is not None:
            data, headers["Content-Type"] = json.dumps(body).encode(), "application/json"
        status, raw, _ = self.http(method, self.server_origin() + self.prefix() + path, data, headers)
        return status, raw, {}

    def websocket_request(self, path: str) -> HTTPRequest:
        origin = self.server_origin()
        full = origin + self.prefix() + path
        xsrf = self.cookie("_xsrf", full) or ""
        url = full.replace("http://", "ws://", 1).replace("https://", "wss://", 1)
        return HTTPRequest(url + ("?_xsrf=%s" % urllib.parse.quote(xsrf) if xsrf else ""),
                           headers={"Cookie": self.cookie_header(full), "Origin": origin})


def _text(raw: bytes) -> str:
    text = raw.decode(errors="replace")
    message = re.search(r"<p[^>]*class=\"[^\"]*error[^\"]*\"[^>]*>(.*?)</p>", text, re.S)
    return (message.group(1).strip() if message else re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", text)))[:500]


class LocalHub:
    """`make hub` on scratch folders and free ports (see the module docstring)."""

    def __init__(self, image: str, work: Path, students: Sequence[str], tas: Sequence[str] = (),
                 extra_config: str = "", env: Optional[Dict[str, str]] = None) -> None:
        self.work = Path(work)
        self.data = self.work / "data"
        self.port = isolation.free_port()
        # the proxy listens on loopback; users open the hub as http://hub.localhost:PORT, their
        # servers at http://<slug>.hub.localhost:PORT (the course's subdomain_host "auto")
        self.bind_url = "http://127.0.0.1:%d" % self.port
        self.url = "http://hub.localhost:%d" % self.port
        self.culler_token = secrets.token_hex(24)
        self.class_list = self.work / "classlist.csv"
        with open(self.class_list, "w", newline="") as out:
            writer = csv.writer(out)
            writer.writerow(["username", "role"])
            writer.writerows([[name, "ta"] for name in tas] + [[name, "student"] for name in students])
        self.config = self.work / "local_hub_config.py"
        self.config.write_text(LOCAL_CONFIG % {
            "course": str(CHECKOUT / "deploy" / "jupyterhub" / "jupyterhub_config.py"),
            "proxy_api_port": isolation.free_port(),
            "culler_token": self.culler_token} + extra_config)
        # as make hub's HUB_ENV: make's variables, and the proxy on PATH
        self.env = dict(os.environ, HUB_DATA=str(self.data), HUB_CLASS_LIST=str(self.class_list), HUB_IMAGE=image,
                        HUB_URL=self.bind_url, PATH="%s:%s" % (CHECKOUT / ".hub" / "node" / "node_modules" / ".bin",
                                                               os.environ.get("PATH", os.defpath)))
        self.env.pop("DOCKER_HOST", None)
        self.env.update(env or {})
        self.socket = "/run/ros-course-hub-local-%d/podman.sock" % os.getpid()
        self.api_port = isolation.free_port()
        self.log = self.work / "hub.log"
        self.proc: Optional[subprocess.Popen] = None

    def start(self) -> str:
        with open(self.log, "ab") as out:
            self.proc = subprocess.Popen(
                [str(CHECKOUT / ".venv-hub" / "bin" / "course-hub"), "--config", str(self.config),
                 "--socket", self.socket, "--api-port", str(self.api_port)],
                env=self.env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True, cwd=str(self.work))
        proc = self.proc
        if not wait_for(lambda: proc.poll() is not None or self.answers(), HUB_START_TIMEOUT_S, 0.2) or \
                proc.poll() is not None:
            raise JupyterError("the hub did not answer at %s; its log ends:\n%s" % (self.url, self.tail()))
        return "%s answers (podman's Docker API on %s)" % (self.url, self.socket)

    def answers(self) -> bool:
        try:
            with urllib.request.urlopen(self.url + "/hub/api/", timeout=5) as reply:
                return reply.status == 200
        except OSError:
            return False

    def tail(self, chars: int = 3000) -> str:
        try:
            return self.log.read_text(errors="replace")[-chars:]
        except OSError:
            return ""

    def stop(self) -> None:
        """The hub stops every server (their containers removed), then podman's API; the students'
        disks it mounted under the scratch folder are unmounted (a spawn or hub_grade mounts them
        again), so that the folder can be removed."""
        if self.proc is not None and self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(HUB_STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        with open("/proc/mounts") as mounts:
            below = [line.split()[1] for line in mounts if line.split()[1].startswith(str(self.work) + "/")]
        for point in sorted(below, reverse=True):
            subprocess.run(["umount", point], check=False)

    def __enter__(self) -> "LocalHub":
        self.start()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.stop()
