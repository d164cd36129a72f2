"""The student's workbench (`make jupyter`) for tests and benchmarks, driven as JupyterLab's own
page drives it: Jupyter's REST API and its terminal websocket.

`Workbench` starts the real start-up (`rosrun course_workbench workbench`, what `make jupyter`
runs) on a free port, with a fresh HOME (the student's home: their overlay ~/catkin_ws is made
there) and a student master URI on a free port nobody else uses, and waits until JupyterLab
answers. Stopping it stops JupyterLab (SIGTERM: it ends its terminals and the proxied lab page),
then anything left that carries its run token (course_testkit.isolation), and removes the home.

`Terminal` is one of JupyterLab's terminals (`POST /api/terminals`, then the websocket
`/terminals/websocket/<name>`, JSON ["stdin", text] in and ["stdout", text] out): `run(command)`
types a command line and returns its exit status and what it printed. It works on any
`JupyterSession`: the workbench with its token here, a hub's user with their login cookies
(course_testkit.hub).
"""
from __future__ import annotations

import asyncio
import json
import os
import re
import secrets
import shutil
import signal
import subprocess
import tempfile
import threading
import time
import urllib.error
import urllib.request
import uuid
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple

from tornado.httpclient import HTTPRequest
from tornado.websocket import websocket_connect

from course_testkit import isolation
from course_testkit.nodes import find_executable
from course_testkit.waiting import wait_for

START_TIMEOUT_S = 60.0
STOP_TIMEOUT_S = 20.0
REQUEST_TIMEOUT_S = 30.0


class WorkbenchError(RuntimeError):
    """The workbench did not start, or a terminal command did not finish in time."""


class JupyterSession:
    """A way into one Jupyter server: `request` (REST) and `websocket_request` (a websocket's URL and
    headers); the REST calls the tests make, and terminals, on top of them."""

    def request(self, method: str, path: str, body: Any = None, token: Optional[str] = "",
                follow: bool = True) -> Tuple[int, bytes, Dict[str, str]]:
        raise NotImplementedError

    def websocket_request(self, path: str) -> HTTPRequest:
        raise NotImplementedError

    def api(self, method: str, path: str, body: Any = None) -> Any:
        """The JSON answer of a REST call that must succeed."""
        status, data, _ = self.request(method, path, body)
        if status >= 300:
            raise WorkbenchError("%s %s -> %d: %s" % (method, path, status, data[:500].decode(errors="replace")))
        return json.loads(data) if data else None

    def write_file(self, path: str, text: str) -> Any:
        """PUT /api/contents/<path>: a text file, relative to JupyterLab's root (the home)."""
        return self.api("PUT", "/api/contents/" + path.lstrip("/"), {"type": "file", "format": "text", "content": text})

    def make_folder(self, path: str) -> Any:
        """PUT /api/contents/<path> as a directory (the file browser's New Folder)."""
        return self.api("PUT", "/api/contents/" + path.lstrip("/"), {"type": "directory"})

    def terminal(self) -> "Terminal":
        name = self.api("POST", "/api/terminals")["name"]
        return Terminal(self, name)


class Workbench(JupyterSession):
    """A running workbench; use as a context manager (see the module docstring)."""

    def __init__(self, env: Optional[Mapping[str, str]] = None, home: Optional[str] = None,
                 token: Optional[str] = None, command: Optional[Sequence[str]] = None) -> None:
        """`command` (default: the start-up itself) may be another way to it, e.g. `make jupyter`."""
        self.command = list(command) if command else None
        self.port = isolation.free_port()
        self.token = token or secrets.token_hex(16)
        self._owns_home = home is None
        # A home others may pass (0755, as /home/<user>): a root grader's sandbox user must reach
        # the self-check's output folder under it.
        self.home = home or tempfile.mkdtemp(prefix="workbench-home-")
        os.chmod(self.home, 0o755)
        self.run_token = isolation.new_token()
        self.master_uri = "http://localhost:%d" % isolation.free_port()
        base = dict(os.environ if env is None else env)
        base.update({"HOME": self.home, "JUPYTER_TOKEN": self.token, "JUPYTER_PORT": str(self.port),
                     "ROS_MASTER_URI": self.master_uri, "ROS_HOSTNAME": "localhost", "PYTHONUNBUFFERED": "1",
                     isolation.TOKEN_VAR: self.run_token})
        for name in ("ROS_IP", "ROS_HOME", "ROS_LOG_DIR", "JUPYTER_ADDRESS", "JUPYTER_URL_HOST", "DISPLAY"):
            base.pop(name, None)
        self.env = base
        self.log_path = os.path.join(self.home, "workbench.log")
        self.proc: Optional[subprocess.Popen] = None
        self.started_s: Optional[float] = None  # from the command to JupyterLab answering

    @property
    def url(self) -> str:
        return "http://127.0.0.1:%d" % self.port

    def output(self) -> str:
        try:
            with open(self.log_path, errors="replace") as log:
                return log.read()
        except OSError:
            return ""

    def start(self) -> "Workbench":
        command = self.command or [find_executable("course_workbench", "workbench")]
        began = time.monotonic()
        with open(self.log_path, "wb") as log:
            self.proc = subprocess.Popen(command, env=self.env, stdin=subprocess.DEVNULL, stdout=log,
                                         stderr=subprocess.STDOUT, start_new_session=True)
        proc = self.proc
        if not wait_for(lambda: proc.poll() is not None or self.status("/api/status") == 200, START_TIMEOUT_S, 0.05) \
                or proc.poll() is not None:
            output = self.output()
            self.stop()
            raise WorkbenchError("the workbench did not start on port %d (exit code %s):\n%s"
                                 % (self.port, proc.poll(), output[-4000:]))
        self.started_s = time.monotonic() - began
        return self

    def stop(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            try:  # JupyterLab (and a `make` above it) ends its terminals and its proxied servers
                os.killpg(self.proc.pid, signal.SIGTERM)
                self.proc.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        # JupyterLab does not wait for the lab page's processes: they end theirs within seconds.
        wait_for(lambda: not isolation.pids_with_token(self.run_token), STOP_TIMEOUT_S, 0.1)
        isolation.kill_run(self.run_token)
        if self._owns_home:
            shutil.rmtree(self.home, ignore_errors=True)

    def __enter__(self) -> "Workbench":
        return self.start()

    def __exit__(self, *exc: Any) -> None:
        self.stop()

    # --- REST ---------------------------------------------------------------------------------

    def request(self, method: str, path: str, body: Any = None, token: Optional[str] = "",
                follow: bool = True) -> Tuple[int, bytes, Dict[str, str]]:
        """(status, body, headers) of a request to JupyterLab; `token` None sends none, "" ours."""
        headers = {}
        if token is not None:
            headers["Authorization"] = "token %s" % (token or self.token)
        data = None
        if body is not None:
            data = json.dumps(body).encode()
            headers["Content-Type"] = "application/json"
        request = urllib.request.Request(self.url + path, data=data, method=method, headers=headers)
        opener = urllib.request.build_opener() if follow else urllib.request.build_opener(_NoRedirect)
        try:
            with opener.open(request, timeout=REQUEST_TIMEOUT_S) as reply:
                return reply.status, reply.read(), dict(reply.headers)
        except urllib.error.HTTPError as err:
            return err.code, err.read(), dict(err.headers)

    def status(self, path: str, token: Optional[str] = "") -> Optional[int]:
        try:
            return self.request("GET", path, token=token, follow=False)[0]
        except OSError:
            return None

    def websocket_request(self, path: str) -> HTTPRequest:
        return HTTPRequest("ws://127.0.0.1:%d%s?token=%s" % (self.port, path, self.token))


class _NoRedirect(urllib.request.HTTPRedirectHandler):
    def redirect_request(self, *args: Any, **kwargs: Any) -> None:
        return None


# Control sequences a terminal prints (colours, titles, bracketed paste), taken out of the output.
_ANSI = re.compile(r"\x1b(\[[0-9;?]*[ -/]*[@-~]|\][^\x07\x1b]*(\x07|\x1b\\)?|[()][A-Za-z0-9])")


class Terminal:
    """One of JupyterLab's terminals, through its websocket (see the module docstring)."""

    def __init__(self, workbench: JupyterSession, name: str) -> None:
        self.workbench, self.name = workbench, name
        # The websocket's loop runs all the time, in a thread of its own: Jupyter pings its
        # terminals' websockets and closes one that leaves its pings unanswered.
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, name="terminal-%s" % name, daemon=True)
        self.thread.start()
        self.pending = ""
        self.socket = self._call(self._connect(workbench.websocket_request("/terminals/websocket/%s" % name)),
                                 REQUEST_TIMEOUT_S)

    def _call(self, coroutine: Any, timeout: float) -> Any:
        """Run `coroutine` on the websocket's loop; its result."""
        return asyncio.run_coroutine_threadsafe(coroutine, self.loop).result(timeout)

    def run(self, command: str, timeout: float = 120.0) -> Tuple[int, str]:
        """Type `command` and Enter; wait for it to finish. (exit status, what it printed)."""
        mark = uuid.uuid4().hex[:12]
        # The typed line holds the marker split in two ('@@''END'), so only the echo's output matches.
        # `a & echo`: a command line that ends in & takes no `;`
        joint = " " if command.rstrip().endswith("&") else "; "
        self._call(self._send(["stdin", "%s%secho \"@@\"'END' $? %s\r" % (command, joint, mark)]), REQUEST_TIMEOUT_S)
        pattern = re.compile(r"@@END (\d+) %s" % mark)
        text = self._call(self._read_until(pattern, timeout), timeout + REQUEST_TIMEOUT_S)
        found = pattern.search(text)
        # what follows the typed line (echoed with the marker in it), up to the marker's output
        typed = text.rfind(mark, 0, found.start())
        start = text.find("\n", typed) + 1 if typed >= 0 else 0
        return int(found.group(1)), text[start:found.start()]

    @staticmethod
    async def _connect(request: HTTPRequest):
        request.connect_timeout = REQUEST_TIMEOUT_S
        return await websocket_connect(request)

    async def _send(self, message: list) -> None:
        await self.socket.write_message(json.dumps(message))

    async def _read_until(self, pattern: "re.Pattern[str]", timeout: float) -> str:
        deadline = time.monotonic() + timeout
        while not pattern.search(self.pending):
            left = deadline - time.monotonic()
            if left <= 0:
                raise WorkbenchError("terminal %s: no end of the command within %.0f s; it printed:\n%s"
                                     % (self.name, timeout, self.pending[-3000:]))
            try:
                message = await asyncio.wait_for(self.socket.read_message(), left)
            except asyncio.TimeoutError:
                continue
            if message is None:
                raise WorkbenchError("terminal %s closed; it printed:\n%s" % (self.name, self.pending[-3000:]))
            kind, *rest = json.loads(message)
            if kind == "stdout":
                self.pending += _ANSI.sub("", rest[0]).replace("\r", "")
        found = pattern.search(self.pending)
        text, self.pending = self.pending[:found.end()], self.pending[found.end():]
        return text

    async def _closed(self) -> None:
        self.socket.close()
        try:
            while await asyncio.wait_for(self.socket.read_message(), STOP_TIMEOUT_S) is not None:
                pass
        except asyncio.TimeoutError:
            pass

    def close(self) -> None:
        """Close the websocket (its closing handshake done), then end the terminal's shell."""
        try:
            self._call(self._closed(), 2 * STOP_TIMEOUT_S)
        finally:
            self.loop.call_soon_threadsafe(self.loop.stop)
            self.thread.join(STOP_TIMEOUT_S)
            self.loop.close()
        self.workbench.request("DELETE", "/api/terminals/%s" % self.name)

    def __enter__(self) -> "Terminal":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()
