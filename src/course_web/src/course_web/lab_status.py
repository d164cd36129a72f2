"""The master watched once for every page, and what changed pushed to the pages that want it.

A page used to poll lab_view's /api/health every second and /api/graph every 2 s through
JupyterLab's proxy, and each question cost lab_view and the master XML-RPC calls (and the canvas's
turtlesim a getPid) although nothing had changed. Now a page says once, on its websocket, what it
wants to be told (`{"op": "lab_status", "health": topic, "graph": true, "debug": false, "topics":
true}`, see course_web.protocol) and LabStatus tells it, as {"op": "lab_status", <part>: <answer>}
frames, each part when it is first known and then only when it changes:

- "health": introspect.health's words about the topic (no master / no publisher / ok);
- "graph": introspect.graph (rqt_graph's view, /rosout shown with "debug");
- "topics": introspect.topics (the camera panels' lists).

While at least one client wants something, a thread of its own asks the master its system state
every `state_period_s` (the one call that notices a master that stopped and a node that came or
went), through a CachedMaster, which asks the topic types only when the state changed and pings a
watched topic's publishers at most every few seconds (a node killed by SIGKILL stays registered:
only asking it tells). With no client, nothing is asked. The /api/... questions answer from the
same cache when it is recent (`answer`), so any number of clients and questions share one round.
"""
from __future__ import annotations

import json
import logging
import math
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Hashable, Optional, Tuple

from course_web import introspect
from course_web.master_cache import CachedMaster

STATE_PERIOD_S = 1.5
"""How often the system state is asked while a page watches: the page's words follow a stopped
master, and its graph a node that came or went, within this (and the call's own time)."""
API_MAX_AGE_S = 0.5
"""An /api/... question is answered from the cache when it is at most this old."""
Deliver = Callable[[str, str], None]
"""deliver(part, frame): hand one lab_status frame to a client (never blocks)."""


@dataclass(frozen=True)
class Wants:
    """What one client asked to be told: the health of a topic (None: not asked; "": the canvas's
    default topic), the graph (with /rosout when `debug`), the topic list."""

    health: Optional[str] = None
    graph: bool = False
    debug: bool = False
    topics: bool = False

    def parts(self) -> Tuple[Tuple[str, Any], ...]:
        """(part, the option its answer depends on) for each part asked."""
        asked = []
        if self.health is not None:
            asked.append(("health", introspect.canvas_topic(self.health)))
        if self.graph:
            asked.append(("graph", self.debug))
        if self.topics:
            asked.append(("topics", None))
        return tuple(asked)


@dataclass
class _Client:
    wants: Wants
    deliver: Deliver
    sent: Dict[str, str] = field(default_factory=dict)  # part -> the frame sent last


def frame(part: str, answer: Dict[str, Any]) -> str:
    return json.dumps({"op": "lab_status", part: answer}, separators=(",", ":"), allow_nan=False)


class LabStatus:
    """See the module docstring. Thread-safe: one lock guards the cache and the clients."""

    def __init__(self, master: introspect.Master, clock: Callable[[], float] = time.monotonic,
                 state_period_s: float = STATE_PERIOD_S, warn: Optional[Callable[[str], None]] = None,
                 threaded: bool = True, **cache_periods: float) -> None:
        """`threaded`: run the rounds on a thread of its own (False: the caller calls step())."""
        self.cache = CachedMaster(master, clock, **cache_periods)
        self.state_period_s = state_period_s
        self.warn = warn or logging.getLogger(__name__).warning
        self.lock = threading.Lock()
        self.wake = threading.Condition(self.lock)
        self.clients: Dict[Hashable, _Client] = {}
        self.thread: Optional[threading.Thread] = None
        self.stopped = not threaded
        self._answers: Dict[Tuple[str, Any], str] = {}  # (part, option) -> frame, for cache.version
        self._answers_version = -1

    # -- clients ---------------------------------------------------------------------------
    def watch(self, client: Hashable, wants: Wants, deliver: Deliver) -> None:
        """From now on tell `client` what it wants (replacing what it wanted before): at once when
        the cache is recent, else after the next round, which starts now."""
        with self.lock:
            self.clients[client] = watcher = _Client(wants, deliver)
            if self.cache.age() < self.state_period_s:
                self._tell(watcher)
            self._start()
            self.wake.notify_all()

    def unwatch(self, client: Hashable) -> None:
        with self.lock:
            self.clients.pop(client, None)

    # -- rounds ----------------------------------------------------------------------------
    def due_in(self) -> Optional[float]:
        """Seconds until the next round is due (0: now); None while nobody watches."""
        with self.lock:
            return self._due_in()

    def _due_in(self) -> Optional[float]:
        if not self.clients:
            return None
        return max(0.0, self.state_period_s - self.cache.age())

    def step(self) -> None:
        """One round: the system state, the watched topics' publishers when due, and what changed
        told to each client."""
        with self.lock:
            if not self.clients:
                return
            self.cache.refresh()
            try:
                state = self.cache.system_state()
            except introspect.ApiError:
                state = None
            if state is not None:
                for wants in {c.wants for c in self.clients.values()}:
                    if wants.health is not None:
                        self.cache.check_nodes(introspect.publishers_of(state, introspect.canvas_topic(wants.health)))
            for watcher in list(self.clients.values()):
                self._tell(watcher)

    def _tell(self, watcher: _Client) -> None:
        """Send the client each part it wants whose answer differs from what it was sent last."""
        if self._answers_version != self.cache.version:
            self._answers, self._answers_version = {}, self.cache.version
        for part, option in watcher.wants.parts():
            key = (part, option)
            if key not in self._answers:
                self._answers[key] = frame(part, self._ask(part, option))
            text = self._answers[key]
            if watcher.sent.get(part) != text:
                watcher.sent[part] = text
                watcher.deliver(part, text)

    def _ask(self, part: str, option: Any) -> Dict[str, Any]:
        try:
            if part == "health":
                return introspect.health(self.cache, option)
            if part == "graph":
                return introspect.graph(self.cache, option)
            return introspect.topics(self.cache)
        except introspect.ApiError as err:
            return {"error": str(err)}

    # -- the /api/... questions ------------------------------------------------------------
    def answer(self, question: Callable[[introspect.Master], Dict[str, Any]],
               max_age_s: float = API_MAX_AGE_S) -> Dict[str, Any]:
        """question(master) answered from the cache, asking the master first when the cache is
        older than `max_age_s`; what that round found changed goes to the watching clients too."""
        with self.lock:
            if self.cache.age() >= max_age_s:
                self.cache.refresh()
                for watcher in list(self.clients.values()):
                    self._tell(watcher)
            return question(self.cache)

    # -- the thread ------------------------------------------------------------------------
    def _start(self) -> None:
        if self.thread is None and not self.stopped:
            self.thread = threading.Thread(target=self._run, name="lab_view-status", daemon=True)
            self.thread.start()

    def stop(self) -> None:
        with self.lock:
            self.stopped = True
            self.wake.notify_all()
        if self.thread is not None and self.thread is not threading.current_thread():
            self.thread.join(10.0)

    def _run(self) -> None:
        failures = 0
        while True:
            with self.lock:
                while True:
                    if self.stopped:
                        return
                    due = self._due_in()
                    if due is not None and due <= 0:
                        break
                    self.wake.wait(due)
            try:
                self.step()
                failures = 0
            except Exception as err:  # noqa: BLE001 - the pages' status must outlive any one failure
                failures += 1
                if failures == 1 or math.log2(failures).is_integer():  # 1st, 2nd, 4th, 8th, ...
                    self.warn("lab_view: watching the master failed (%d times in a row): %r" % (failures, err))
