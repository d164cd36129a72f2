"""A JupyterLab server driven as JupyterLab's own page drives it: Jupyter's REST API and its terminal
websocket. No client of our own beyond these few calls: Jupyter's API, tornado's websocket.

`JupyterSession` is a way into one Jupyter server: `request` (REST) and `websocket_request` (a
websocket's URL and headers), and the calls the tests make on top of them. `JupyterServer(port,
token)` is one reached with its token (the workbench started by course_testkit.workbench, or one in
a container with its port published); course_testkit.hub's `HubUser` one reached through a hub with
a user's login cookies. `terminal()` is one of its terminals (`POST /api/terminals`, then the websocket `/terminals/websocket/<name>`, JSON
["stdin", text] in and ["stdout", text] out): `run(command)` types a command line and returns its
exit status and what it printed.

Needs tornado alone (Debian's python3-tornado), no ROS: the podman suites (tests/e2e/test_image.py)
use it with Debian's python3 outside the workspace.
"""
from __future__ import annotations

import asyncio
import json
import re
import threading
import time
import urllib.error
import urllib.request
import uuid
from typing import Any, Dict, Optional, Tuple

import tornado.httpclient
from tornado.httpclient import HTTPRequest
from tornado.websocket import WebSocketError, websocket_connect

STOP_TIMEOUT_S = 20.0
REQUEST_TIMEOUT_S = 30.0


class JupyterError(RuntimeError):
    """The server did not start or refused a call, or a terminal command did not finish in time."""


class JupyterSession:
    """A way into one Jupyter server (see the module docstring)."""

    def request(self, method: str, path: str, body: Any = None, token: Optional[str] = "",
                follow: bool = True) -> Tuple[int, bytes, Dict[str, str]]:
        """(status, body, headers) of a request to the server, at `path` under its base."""
        raise NotImplementedError

    def websocket_request(self, path: str) -> HTTPRequest:
        """The websocket request (URL, headers) for `path` under the server's base."""
        raise NotImplementedError

    def status(self, path: str, token: Optional[str] = "") -> Optional[int]:
        try:
            return self.request("GET", path, token=token, follow=False)[0]
        except OSError:
            return None

    def api(self, method: str, path: str, body: Any = None) -> Any:
        """The JSON answer of a REST call that must succeed."""
        status, data, _ = self.request(method, path, body)
        if status >= 300:
            raise JupyterError("%s %s -> %d: %s" % (method, path, status, data[:500].decode(errors="replace")))
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

    def desktop_greeting(self, timeout: float = 60.0) -> bytes:
        """The first message of the desktop's websocket (jupyter-remote-desktop-proxy's
        `/desktop-websockify/`): the VNC server's protocol version (b"RFB 003.008\\n"), which
        arrives only once the proxy has started the X session's VNC server."""
        async def greet() -> bytes:
            socket = await connect(self.websocket_request("/desktop-websockify/"), timeout)
            try:
                message = await asyncio.wait_for(socket.read_message(), timeout)
            finally:
                socket.close()
            if message is None:
                raise JupyterError("the desktop's websocket closed before the VNC server spoke")
            return message if isinstance(message, bytes) else message.encode()
        return asyncio.run(greet())


class JupyterServer(JupyterSession):
    """A running Jupyter server at 127.0.0.1:`port`, whose token is `token`."""

    def __init__(self, port: int, token: str) -> None:
        self.port, self.token = port, token

    @property
    def url(self) -> str:
        return "http://127.0.0.1:%d" % self.port

    def websocket_request(self, path: str) -> HTTPRequest:
        return HTTPRequest("ws://127.0.0.1:%d%s?token=%s" % (self.port, path, self.token))

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


async def connect(request: HTTPRequest, timeout: float = REQUEST_TIMEOUT_S) -> Any:
    """A websocket to a session's `websocket_request`, its handshake given `timeout` seconds."""
    request.connect_timeout = timeout
    return await websocket_connect(request)


def refused_websocket(url: str) -> Optional[int]:
    """The HTTP status that refused the websocket handshake at `url` (-1: refused without one;
    None: it was accepted)."""
    async def connect() -> Optional[int]:
        try:
            socket = await websocket_connect(url, connect_timeout=REQUEST_TIMEOUT_S)
        except WebSocketError:
            return -1
        except tornado.httpclient.HTTPClientError as err:
            return err.code
        socket.close()
        return None
    return asyncio.run(connect())


class _NoRedirect(urllib.request.HTTPRedirectHandler):
    def redirect_request(self, *args: Any, **kwargs: Any) -> None:
        return None


# Control sequences a terminal prints (colours, titles, bracketed paste), taken out of the output.
_ANSI = re.compile(r"\x1b(\[[0-9;?]*[ -/]*[@-~]|\][^\x07\x1b]*(\x07|\x1b\\)?|[()][A-Za-z0-9])")


class Terminal:
    """One of JupyterLab's terminals, through its websocket (see the module docstring)."""

    def __init__(self, server: JupyterSession, name: str) -> None:
        self.server, self.name = server, name
        # The websocket's loop runs all the time, in a thread of its own: Jupyter pings its
        # terminals' websockets and closes one that leaves its pings unanswered.
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, name="terminal-%s" % name, daemon=True)
        self.thread.start()
        self.pending = ""
        self.socket = self._call(connect(server.websocket_request("/terminals/websocket/%s" % name)),
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

    async def _send(self, message: list) -> None:
        await self.socket.write_message(json.dumps(message))

    async def _read_until(self, pattern: "re.Pattern[str]", timeout: float) -> str:
        deadline = time.monotonic() + timeout
        while not pattern.search(self.pending):
            left = deadline - time.monotonic()
            if left <= 0:
                raise JupyterError("terminal %s: no end of the command within %.0f s; it printed:\n%s"
                                     % (self.name, timeout, self.pending[-3000:]))
            try:
                message = await asyncio.wait_for(self.socket.read_message(), left)
            except asyncio.TimeoutError:
                continue
            if message is None:
                raise JupyterError("terminal %s closed; it printed:\n%s" % (self.name, self.pending[-3000:]))
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
        self.server.request("DELETE", "/api/terminals/%s" % self.name)

    def __enter__(self) -> "Terminal":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()
