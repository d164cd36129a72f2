"""The HTTP and websocket server: the page's files and one rosbridge v2 session per socket.

Tornado (Debian's python3-tornado, rosbridge_server's own choice) runs everything network-side
on one asyncio loop. Each socket has a sender task that takes due messages from its Outbox and
awaits each write, so a client that reads slowly only fills (and drops from) its own bounded
queues; the ROS callbacks just append and wake the sender. Requests are handled in a thread
pool, one at a time per socket (tornado awaits on_message), because advertise and subscribe talk
to the master and must not stall the loop. The websocket answers at "/" (where roslibpy and
roslibjs connect, like rosbridge on its port) and at "/websocket"; a plain GET of "/" is the page.
The page's header, graph and camera lists come on its socket too (the lab_status op: one watch
of the master for every client, course_web.lab_status); the /api/... questions stay for other
clients and answer from the same watch's cache when it is recent.
"""
from __future__ import annotations

import concurrent.futures
import datetime
import itertools
import json
import os
import time
from typing import Any, Callable, Dict, Optional

import tornado.locks
import tornado.util
import tornado.web
import tornado.websocket
from tornado.ioloop import IOLoop

from course_web import access, introspect
from course_web.lab_status import LabStatus
from course_web.outbox import Outbox
from course_web.protocol import DEFAULT_MAX_MESSAGE_BYTES, Bridge, Session

TOKEN_COOKIE = "course_web_token"
REQUEST_WORKERS = 8
PING_INTERVAL_S = 20.0
TOKEN_REFUSAL = "a valid token is required: open the URL the lab_view server printed (it ends in ?token=...)"
POLICY_VIOLATION = 1008
CONTENT_TYPES = {".html": "text/html", ".js": "text/javascript", ".css": "text/css"}
"""The kinds of file the page has, as Debian's /etc/mime.types names them. tornado asks mimetypes,
whose first question reads all of /etc/mime.types into tables that stay for the life of the process
(about 0.35 MiB in every student's lab_view); any other file is still asked of mimetypes."""


class Settings:
    """What the handlers share: the bridge, the token, the limits, the page's folder, and the one
    watch of the master (none without a master)."""

    def __init__(self, bridge: Bridge, www: str, token: Optional[str] = None,
                 max_message_bytes: int = DEFAULT_MAX_MESSAGE_BYTES,
                 master: Optional[introspect.Master] = None, warn: Optional[Callable[[str], None]] = None) -> None:
        self.bridge, self.www, self.token, self.max_message_bytes = bridge, www, token, max_message_bytes
        self.status = LabStatus(master, warn=warn) if master is not None else None
        self.requests = concurrent.futures.ThreadPoolExecutor(REQUEST_WORKERS, thread_name_prefix="lab_view-req")
        self.clients = itertools.count(1)
        self.sockets = set()


def presented_token(handler: tornado.web.RequestHandler) -> Optional[str]:
    return handler.get_query_argument(access.TOKEN_PARAM, None) or handler.get_cookie(TOKEN_COOKIE)


class TokenGuard:
    """Mixin: refuse HTTP requests without the token (when one is required)."""

    settings_: Settings

    def guard(self) -> bool:
        if access.allowed(self.settings_.token, presented_token(self)):
            if self.settings_.token is not None and self.get_query_argument(access.TOKEN_PARAM, None):
                self.set_cookie(TOKEN_COOKIE, self.settings_.token, httponly=True, samesite="Strict")
            return True
        self.set_status(403)
        self.set_header("Content-Type", "text/plain; charset=utf-8")
        self.finish(TOKEN_REFUSAL + "\n")
        return False


class StaticFiles(TokenGuard, tornado.web.StaticFileHandler):
    """The page's files, behind the token."""

    def initialize(self, settings_: Settings, **kwargs) -> None:
        self.settings_ = settings_
        super().initialize(path=settings_.www, **kwargs)

    async def get(self, path: str, include_body: bool = True) -> None:
        if self.guard():
            await super().get(path, include_body)

    def set_extra_headers(self, path: str) -> None:
        self.set_header("Cache-Control", "no-cache")

    def get_content_type(self) -> str:
        known = CONTENT_TYPES.get(os.path.splitext(self.absolute_path or "")[1].lower())
        return known or super().get_content_type()


class Api(TokenGuard, tornado.web.RequestHandler):
    """GET /api/graph, /api/topics, /api/plot?path=..., /api/health?topic=...: JSON for the page's panels.

    They are answered on the request pool (the master may have to be asked, and XML-RPC blocks),
    from the cache the pages' watch shares (course_web.lab_status) when it is recent; a failure is a
    JSON {"error": ...} with a 4xx/5xx status, never an exception out of the handler."""

    QUESTIONS: Dict[str, Callable[[introspect.Master, Dict[str, str]], Dict[str, Any]]] = {
        "graph": lambda master, params: introspect.graph(master, params["debug"] == "true"),
        "topics": lambda master, params: introspect.topics(master),
        "plot": lambda master, params: introspect.plot_fields(master, params["path"]),
        "health": lambda master, params: introspect.health(master, params["topic"]),
    }

    def initialize(self, settings_: Settings) -> None:
        self.settings_ = settings_

    async def get(self, question: str) -> None:
        if not self.guard():
            return
        self.set_header("Content-Type", "application/json; charset=utf-8")
        self.set_header("Cache-Control", "no-store")
        status = self.settings_.status
        try:
            try:  # read here, on the loop's thread; tornado refuses arguments that are not UTF-8
                params = {name: self.get_query_argument(name, "") for name in ("debug", "path", "topic")}
            except tornado.web.HTTPError as err:
                raise introspect.ApiError("the request's arguments are not valid UTF-8 text (%s)"
                                          % (err.log_message or err.reason or err.status_code))
            if status is None:
                raise introspect.ApiError("this server has no ROS master to ask", 503)
            ask = self.QUESTIONS[question]
            answer = await IOLoop.current().run_in_executor(self.settings_.requests, status.answer,
                                                            lambda master: ask(master, params))
        except introspect.ApiError as err:
            self.set_status(err.status)
            answer = {"error": str(err)}
        except Exception as err:  # noqa: BLE001 - a page's question must not break the server
            self.set_status(500)
            answer = {"error": "%s failed inside the server: %r" % (question, err)}
        self.finish(json.dumps(answer))


class BridgeSocket(TokenGuard, tornado.websocket.WebSocketHandler):
    """One client: a Session, its Outbox and the task that sends what is due."""

    def initialize(self, settings_: Settings) -> None:
        self.settings_ = settings_
        self.session: Optional[Session] = None
        self.outbox = Outbox()
        self.wake_event = tornado.locks.Event()
        self.loop = IOLoop.current()
        self.closed = False

    async def get(self, *args, **kwargs) -> None:
        if self.request.headers.get("Upgrade", "").lower() != "websocket":
            if self.guard():  # a browser asking for the page itself
                self.set_header("Cache-Control", "no-cache")
                with open(os.path.join(self.settings_.www, "index.html"), "rb") as page:
                    self.set_header("Content-Type", "text/html; charset=utf-8")
                    self.finish(page.read())
            return
        await super().get(*args, **kwargs)

    def open(self, *args, **kwargs) -> None:
        if not access.allowed(self.settings_.token, presented_token(self)):
            self.close(POLICY_VIOLATION, TOKEN_REFUSAL)
            return
        self.session = Session(next(self.settings_.clients), self.settings_.bridge, self.outbox,
                               self.settings_.max_message_bytes, self.wake, self.settings_.status)
        self.settings_.sockets.add(self)
        self.loop.spawn_callback(self.send_loop)

    async def on_message(self, message) -> None:
        if self.session is not None:
            await self.loop.run_in_executor(self.settings_.requests, self.session.handle, message)

    def wake(self) -> None:
        """Called from any thread when the outbox has something new."""
        if not self.wake_event.is_set():
            self.loop.add_callback(self.wake_event.set)

    async def send_loop(self) -> None:
        while not self.closed:
            payload = self.outbox.take(time.monotonic())
            if payload is None:
                self.wake_event.clear()
                due = self.outbox.next_due(time.monotonic())
                if due == 0.0:
                    continue
                try:
                    await self.wake_event.wait(None if due is None else datetime.timedelta(seconds=due))
                except tornado.util.TimeoutError:
                    pass
                continue
            try:
                await self.write_message(payload, binary=isinstance(payload, bytes))
            except tornado.websocket.WebSocketClosedError:
                break

    def on_close(self) -> None:
        self.closed = True
        self.wake_event.set()
        self.settings_.sockets.discard(self)
        if self.session is not None:
            self.settings_.requests.submit(self.session.close)


def application(settings: Settings) -> tornado.web.Application:
    """The tornado application serving the page and the websocket."""
    return tornado.web.Application(
        [(r"/(?:websocket)?", BridgeSocket, {"settings_": settings}),
         (r"/api/(graph|topics|plot|health)", Api, {"settings_": settings}),
         (r"/(.+)", StaticFiles, {"settings_": settings})],
        # Frames up to 2x the limit are read and answered with a status error; beyond that
        # tornado closes the socket (1009, "message too big") without reading them.
        websocket_max_message_size=2 * settings.max_message_bytes + 1024,
        websocket_ping_interval=PING_INTERVAL_S)
