#!/usr/bin/env python3
"""The class's hub on this machine, measured: figures printed, nothing asserted (root, podman).

Three modes, each on hubs of its own (course_testkit's LocalHub: `make hub` on scratch folders):

**--steady**: what one student costs once settled, per process. One student per image (`--image`,
and `--before-image` beside it: two hubs at once, the two containers measured over the same
windows, so load hits both alike), each with their own headless chromium logged in to the hub,
through four states:

1. idle: JupyterLab open in the browser, a terminal open (the REST terminal), nothing running;
2. turtlesim moving: in that terminal roscore, turtlesim and `rostopic pub -r 10` of a turning
   Twist (the turtle drives in circles);
3. lab page open: the same, and the lab page (`/user/<name>/roslab/`) open in a second tab of the
   browser: the page itself, whatever it subscribes to and polls;
4. desktop open: the same, the lab page's tab closed and the desktop (`/desktop/`, noVNC)
   connected in it.

After each change the containers settle (2 s windows of CPU until two in a row agree within 1
point of a core or 15 %, 10-90 s), then one window of --steady-window seconds (30): CPU from the
container's cgroup counter (the delta over the window: not averaged since the start as `podman
stats` does), memory as the cgroup's use less its file pages (course_testkit.hub_cost), and both split
by process (JupyterLab, master, rosout, turtlesim, lab view, Xvnc, the student's own commands, ...:
/proc/PID/stat and RssAnon), and the hub's own processes' CPU (JupyterHub, the proxy, podman's
API). The load average is printed with each window.

**--peak K**: K students press Start at the same moment (the top of a lab session): each spawn's
time to JupyterLab answering, the spawn rate (servers ready a minute), start-up CPU and memory
per student, the hub's CPU, the load average.

**the sweep** (default): N students, added --step at a time: each logs in over HTTP, starts their
server, runs the terminal's turtlesim as in state 2, and has the lab page open: its websocket
through the hub and its API questions as the real page sends them (recorded for --record s from
chromium on the first student's page, then replayed by every student: PageTraffic). At each N:

- cost: every container settled as above, then their cgroups' counters over --steady-window: the
  mean memory and CPU per student, the hub's CPU;
- turtlesim's tick rate: every student's /turtle1/pose counted for --window seconds at once, by
  a subscriber in their own container (rospy, in a terminal); the slowest student's rate, and the
  longest gap between two poses;
- the lab pages' messages per second (the slowest page), to show the pages were live;
- the hub's page latency: GET /hub/home and GET /user/<name>/api/status (through the proxy), 20
  of each, median and worst;
- the machine's load average.

The largest N at which every turtlesim holds >= 60 Hz and the hub answers within 1 s is printed,
with the spawn time of one server and what a class of 300 needs, steady, from these figures.

    sudo python3 bench/hub_bench.py --steady --image localhost/ros-course-hub-after \
        --before-image localhost/ros-course-hub-before
    sudo python3 bench/hub_bench.py --peak 20 --image localhost/ros-course-hub-after
    sudo python3 bench/hub_bench.py --image localhost/ros-course-hub-after --max 30 --step 5

Run from a sourced workspace (course_testkit). This machine: 2 cores shared with other work,
so the figures are a floor, not what a dedicated node gives.
"""
from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Tuple

from tornado.websocket import websocket_connect

from course_hub import passwords
from course_hub.names import container as container_name
from course_checks.waiting import wait_for
from course_testkit.browser import chromium
from course_testkit.hub import HubUser, LocalHub
from course_testkit.jupyter import JupyterError

from course_testkit.hub_cost import MIB, Cgroup, Meter, Window, container_pid, loadavg, tree_cpu_s, settle, windows

PODMAN = ["podman", "--runtime", "runc", "--cgroup-manager=cgroupfs"]
MIN_RATE_HZ = 60.0
MAX_LATENCY_S = 1.0
CLASS = 300
POSE_RATE = '''import sys, time, rospy
from turtlesim.msg import Pose
stamps = []
rospy.init_node("pose_rate", anonymous=True)
rospy.Subscriber("/turtle1/pose", Pose, lambda m: stamps.append(time.monotonic()), queue_size=100)
rospy.wait_for_message("/turtle1/pose", Pose, timeout=30)
stamps.clear()
time.sleep(float(sys.argv[1]))
gaps = [b - a for a, b in zip(stamps, stamps[1:])]
print("RATE %.2f GAP %.1f" % ((len(stamps) - 1) / (stamps[-1] - stamps[0]), 1000 * max(gaps)))
'''
MOVE = ("(rostopic pub -r 10 /turtle1/cmd_vel geometry_msgs/Twist "
        "'{linear: {x: 1.0}, angular: {z: 0.8}}' > /dev/null 2>&1 &)")


# Put in every page before its own scripts run: what the page sends on its websockets and which
# URLs it fetches, with when (read back by PageTraffic.record).
RECORDER = """
window.__sent = []; window.__asked = [];
const send = WebSocket.prototype.send;
WebSocket.prototype.send = function (data) {
  window.__sent.push([performance.now(), typeof data === 'string' ? data : null]);
  return send.call(this, data);
};
const fetchOriginal = window.fetch;
window.fetch = function (url, options) {
  window.__asked.push([performance.now(), String(url instanceof Request ? url.url : url)]);
  return fetchOriginal.apply(this, arguments);
};
"""


class PageTraffic:
    """What the lab page asks of its server, as a real browser showed it: the websocket messages
    it sends once (subscriptions, advertisements) and those it repeats, the API questions it polls,
    each repeated one with its period. Recorded from headless chromium on one student's page, then
    replayed by each LabPage: the sweep's pages follow whatever the page does (course_web's www/)."""

    # what the page did before this recorder (the sweep's fixed mimic when no browser is here)
    FALLBACK = ([(json.dumps({"op": "subscribe", "id": "canvas", "topic": "/turtlesim/image", "type": "sensor_msgs/Image",
                              "compression": "jpeg", "queue_length": 1}), 0.0),
                 (json.dumps({"op": "subscribe", "id": "console", "topic": "/rosout", "type": "rosgraph_msgs/Log"}), 0.0)],
                [("api/graph", 2.0), ("api/health?topic=%2Fturtlesim%2Fimage", 1.0)])

    def __init__(self, frames: List[Tuple[str, float]], polls: List[Tuple[str, float]], source: str) -> None:
        self.frames, self.polls, self.source = frames, polls, source  # (text or path, period s; 0 = once)

    @classmethod
    def record(cls, hub: LocalHub, student: "Student", seconds: float) -> "PageTraffic":
        try:
            with contextlib.ExitStack() as stack:
                browser = Browser(stack, hub, student)
                browser.driver.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": RECORDER})
                browser.driver.get(browser.base + "roslab/")  # in this tab, where the recorder is put
                if not page_ready(browser.driver, LAB_PAGE_READY, 120):
                    raise RuntimeError("the lab page did not get ready")
                time.sleep(seconds)
                sent, asked, now = browser.driver.execute_script(
                    "return [window.__sent, window.__asked, performance.now()];")
        except Exception as err:  # no chromium here: the fixed mimic, said so
            return cls(*cls.FALLBACK, source="fixed (no browser: %s)" % str(err).splitlines()[0][:120])
        span = now / 1000.0

        def periods(items: List[Tuple[float, str]]) -> List[Tuple[str, float]]:
            counts: Dict[str, int] = {}
            for _, item in items:
                counts[item] = counts.get(item, 0) + 1
            return [(item, 0.0 if n == 1 else span / n) for item, n in counts.items()]
        polls = [(url.split("/roslab/", 1)[1], period) for url, period in
                 periods([(t, u) for t, u in asked if "/roslab/" in u])]
        return cls(periods([(t, text) for t, text in sent if text]), polls,
                   source="recorded from chromium on %s's lab page for %.0f s" % (student.user.name, span))

    def __str__(self) -> str:
        def listed(items: List[Tuple[str, float]]) -> str:
            return "; ".join("%s%s" % (text[:90], " every %.1f s" % period if period else "") for text, period in items)
        return "%s: sends %s; asks %s" % (self.source, listed(self.frames), listed(self.polls))


class LabPage:
    """The lab page of one student, open: its websocket through the hub read all the time, sent
    what the page sends, and its API questions asked as often (PageTraffic)."""

    def __init__(self, user: HubUser, traffic: PageTraffic) -> None:
        self.user = user
        self.traffic = traffic
        self.frames = 0
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()
        status, _, _ = user.http("GET", "/user/%s/roslab/" % user.name)
        if status != 200:
            raise RuntimeError("%s's lab page -> %d" % (user.name, status))
        self.socket = asyncio.run_coroutine_threadsafe(self._open(), self.loop).result(60)
        asyncio.run_coroutine_threadsafe(self._read(), self.loop)
        self.stop = threading.Event()
        for path, period in traffic.polls:
            threading.Thread(target=self._poll, args=(path, period), daemon=True).start()

    async def _open(self):
        socket = await websocket_connect(self.user.websocket_request("/roslab/websocket"))
        for text, _ in self.traffic.frames:
            await socket.write_message(text)
        for text, period in self.traffic.frames:
            if period:
                asyncio.ensure_future(self._repeat(socket, text, period))
        return socket

    async def _repeat(self, socket, text: str, period: float) -> None:
        while not self.stop.is_set():
            await asyncio.sleep(period)
            await socket.write_message(text)

    async def _read(self) -> None:
        while await self.socket.read_message() is not None:
            self.frames += 1

    def _poll(self, path: str, period: float) -> None:
        base = self.user.server_origin() + "/user/%s/roslab/" % self.user.name
        self.user.http("GET", base + path)
        while period and not self.stop.wait(period):
            self.user.http("GET", base + path)

    def close(self) -> None:
        self.stop.set()
        self.loop.call_soon_threadsafe(self.socket.close)
        self.loop.call_soon_threadsafe(self.loop.stop)


class Student:
    """One student logged in, their server started and JupyterLab opened over HTTP, a terminal open;
    given the page's traffic, turtlesim moving and the lab page open (the capacity sweep)."""

    def __init__(self, hub: LocalHub, name: str, password: str, traffic: Optional[PageTraffic] = None) -> None:
        self.user = HubUser(hub.url, name, password)
        self.user.login()
        self.spawn_s = self.user.start()
        status, url = self.user.open_server()  # JupyterLab's page: the hub's OAuth, the server's cookies
        if status != 200:
            raise RuntimeError("%s's JupyterLab -> %d (%s)" % (name, status, url))
        self.term = self.user.terminal()
        self.page: Optional[LabPage] = None
        if traffic:
            self.move_turtle()
            self.page = LabPage(self.user, traffic)

    def move_turtle(self) -> None:
        """roscore, turtlesim and the turning Twist, typed in the terminal."""
        self.user.write_file("pose_rate.py", POSE_RATE)
        code, said = self.term.run("(roscore > ~/roscore.log 2>&1 &) ; until rostopic list > /dev/null 2>&1; do "
                                   "sleep 0.2; done; (rosrun turtlesim turtlesim_node > ~/turtlesim.log 2>&1 &) ; "
                                   "until rostopic list | grep -q /turtle1/pose; do sleep 0.2; done; " + MOVE,
                                   timeout=180)
        if code != 0:
            raise RuntimeError("%s: %s" % (self.user.name, said))

    def meter(self, hub: LocalHub) -> Meter:
        return Meter(container_name(self.user.name), PODMAN, hub.proc.pid if hub.proc else None)

    def close(self) -> None:
        try:
            if self.page:
                self.page.close()
            self.term.close()
        except Exception:
            pass

    def pose_rate(self, window: float) -> Tuple[float, float]:
        try:
            code, said = self.term.run("python3 ~/pose_rate.py %g" % window, timeout=window + 120)
        except JupyterError as err:  # a terminal idle for minutes was closed on the server's side: a new one
            if "closed" not in str(err):
                raise
            self.term = self.user.terminal()
            code, said = self.term.run("python3 ~/pose_rate.py %g" % window, timeout=window + 120)
        found = re.search(r"RATE ([\d.]+) GAP ([\d.]+)", said)
        if not found:
            raise RuntimeError("%s: %s" % (self.user.name, said[-500:]))
        return float(found.group(1)), float(found.group(2))


def rates(students: List[Student], window: float) -> List[Tuple[float, float]]:
    results: List[Optional[Tuple[float, float]]] = [None] * len(students)
    errors: List[str] = []

    def one(i: int) -> None:
        try:
            results[i] = students[i].pose_rate(window)
        except Exception as err:  # reported with the figures
            errors.append(str(err))
    threads = [threading.Thread(target=one, args=(i,)) for i in range(len(students))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if errors:
        raise RuntimeError("; ".join(errors))
    return [r for r in results if r is not None]


def latency(user: HubUser, path: str, count: int = 20) -> Tuple[float, float]:
    times = []
    for _ in range(count):
        began = time.monotonic()
        status, _, _ = user.http("GET", path)
        times.append(time.monotonic() - began if status == 200 else math.inf)
    return statistics.median(times), max(times)


def page_ready(browser, script: str, timeout: float) -> bool:
    return bool(wait_for(lambda: browser.execute_script(script), timeout, 0.5))


class Browser:
    """A student's own headless chromium, logged in to the hub: JupyterLab open in its first tab,
    the lab page or the desktop in a second, as the student opens them."""

    def __init__(self, stack: contextlib.ExitStack, hub: LocalHub, student: Student) -> None:
        self.driver = stack.enter_context(chromium(arguments=("--disable-background-timer-throttling",
                                                              "--disable-renderer-backgrounding")))
        self.user = student.user
        self.driver.get(hub.url + "/hub/login")
        self.driver.find_element("name", "username").send_keys(self.user.name)
        self.driver.find_element("name", "password").send_keys(self.user.password)
        self.driver.find_element("id", "login_submit").click()
        if not wait_for(lambda: "/hub/login" not in self.driver.current_url, 60, 0.2):
            raise RuntimeError("%s's browser login: %s" % (self.user.name, self.driver.current_url))
        self.driver.get(hub.url + "/user/%s/lab" % self.user.name)
        if not page_ready(self.driver, "return !!document.querySelector('.jp-LabShell')", 180):
            raise RuntimeError("%s's JupyterLab did not show: %s" % (self.user.name, self.driver.current_url))
        where = urllib.parse.urlparse(self.driver.current_url)
        self.base = "%s://%s/user/%s/" % (where.scheme, where.netloc, self.user.name)
        self.lab_tab = self.driver.current_window_handle

    def open_tab(self, path: str, ready: str, what: str) -> None:
        self.close_tab()
        self.driver.switch_to.new_window("tab")
        self.driver.get(self.base + path)
        if not page_ready(self.driver, ready, 120):
            raise RuntimeError("%s's %s did not get ready at %s" % (self.user.name, what, self.driver.current_url))

    def close_tab(self) -> None:
        for handle in self.driver.window_handles:
            if handle != self.lab_tab:
                self.driver.switch_to.window(handle)
                self.driver.close()
        self.driver.switch_to.window(self.lab_tab)


# what the lab page and the desktop show once they work: the page's own markers (course_web's
# www/: body[data-ready], the connection badge), noVNC's status line
LAB_PAGE_READY = ("const c = document.getElementById('connection'); "
                  "return document.body.dataset.ready === 'true' && (!c || c.dataset.state === 'open');")
DESKTOP_READY = "const s = document.getElementById('status'); return !!s && s.textContent === 'Connected';"
STATES = ("idle", "turtlesim moving", "lab page open", "desktop open")
STATE_HELP = {
    "idle": "JupyterLab open in the browser and a terminal open, nothing running",
    "turtlesim moving": "roscore, turtlesim and rostopic pub -r 10 of a turning Twist, typed in the terminal",
    "lab page open": "the same, and the lab page (/roslab/) open in a second tab",
    "desktop open": "the same, the lab page's tab closed and the desktop (/desktop/, noVNC) open in it",
}


def enter_state(state: str, student: Student, browser: Browser) -> None:
    if state == "turtlesim moving":
        student.move_turtle()
    elif state == "lab page open":
        browser.open_tab("roslab/", LAB_PAGE_READY, "lab page")
    elif state == "desktop open":
        browser.open_tab("desktop/", DESKTOP_READY, "desktop")


def describe(label: str, w: Window) -> str:
    return "%s CPU %5.1f%% of a core, memory %4.0f MiB (kernel %2.0f), hub %4.1f%%" % (
        label, w.cpu_pct, w.memory_mib, w.kernel_mib, w.hub_cpu_pct)


def breakdown(labels: List[str], found: List[Window]) -> List[str]:
    names = sorted({n for w in found for n in w.by_group}, key=lambda n: -max(w.by_group.get(n, (0, 0))[0]
                                                                                 for w in found))
    rows = []
    for name in names:
        parts = ["%s %5.1f%% %4.0f MiB" % (label, *w.by_group.get(name, (0.0, 0.0))) for label, w in zip(labels, found)]
        rows.append("    %-30s %s" % (name, "   ".join(parts)))
    return rows


@contextlib.contextmanager
def scratch_hubs(classes: List[Tuple[str, List[str]]]) -> Iterator[List[LocalHub]]:
    """A LocalHub for each (image, students), started, on a scratch folder and a podman socket of
    its own; stopped (their containers removed) and the folder removed however the run ends."""
    work = Path(tempfile.mkdtemp(prefix="hub-bench-"))
    os.chmod(work, 0o755)
    hubs: List[LocalHub] = []
    try:
        for number, (image, names) in enumerate(classes):
            folder = work / str(number)
            folder.mkdir()
            os.chmod(folder, 0o755)
            hubs.append(LocalHub(image, folder, names))
            hubs[-1].socket = "/run/ros-course-hub-local-%d-%d/podman.sock" % (os.getpid(), number)
            hubs[-1].start()
        yield hubs
    finally:
        for hub in hubs:
            hub.stop()
        shutil.rmtree(work, ignore_errors=True)


def closing(students: List[Student]) -> contextlib.ExitStack:
    stack = contextlib.ExitStack()
    stack.callback(lambda: [s.close() for s in students])
    return stack


def steady(opts: argparse.Namespace) -> int:
    """Each image's student through the four states, measured side by side (module docstring)."""
    images = [("after", opts.image), ("before", opts.before_image)] if opts.before_image else [("image", opts.image)]
    students: List[Student] = []
    with scratch_hubs([(image, [label[0] + "01"]) for label, image in images]) as hubs, closing(students) as stack:
        print("hub_bench --steady: %s; settle: CPU of 2 s windows within 1 point of a core or 15%% "
              "(10-90 s), then a %.0f s window; load average %s" % (
                  ", ".join("%s %s at %s" % (label, image, h.url) for (label, image), h in zip(images, hubs)),
                  opts.steady_window, loadavg()), flush=True)
        for (label, _), hub in zip(images, hubs):
            name = label[0] + "01"
            handed = passwords.handed_out(str(hub.data))[name]
            students.append(Student(hub, name, handed))
            print("  %s: spawn %.1f s (load average %s)" % (label, students[-1].spawn_s, loadavg()), flush=True)
        browsers = [Browser(stack, hub, s) for hub, s in zip(hubs, students)]
        meters = [s.meter(hub) for hub, s in zip(hubs, students)]
        labels = [label for label, _ in images]
        summary = []
        for state in STATES:
            for student, browser in zip(students, browsers):
                enter_state(state, student, browser)
            waited = settle(meters)
            found = windows(meters, opts.steady_window)
            summary.append((state, found))
            line = "  | ".join(describe(label, w) for label, w in zip(labels, found))
            if len(found) == 2:
                line += "  | after/before CPU %.2f memory %.2f" % (
                    found[0].cpu_pct / max(found[1].cpu_pct, 1e-9), found[0].memory_mib / found[1].memory_mib)
            print("%-17s %s  (settled %.0f s, window %.0f s, load average %s)" % (
                state, line, waited, found[0].seconds, found[0].load), flush=True)
            print("\n".join(breakdown(labels, found)), flush=True)
        print("hub_bench --steady: the states: " + "; ".join("%s: %s" % (s, STATE_HELP[s]) for s in STATES))
        for (state, found) in summary:
            print("  %-17s %s" % (state, "  ".join("%s %.1f%% / %.0f MiB" % (label, w.cpu_pct, w.memory_mib)
                                                     for label, w in zip(labels, found))))
    return 0


def peak(opts: argparse.Namespace) -> int:
    """--peak K: K students press Start at the same moment (the top of a lab session), twice: their
    first start (the hub makes each one's disk), then, all stopped, again (a later session)."""
    names = ["p%02d" % i for i in range(1, opts.peak + 1)]
    with scratch_hubs([(opts.image, names)]) as (hub,):
        handed = passwords.handed_out(str(hub.data))
        users = [HubUser(hub.url, name, handed[name]) for name in names]
        for user in users:
            user.login()
        print("hub_bench --peak: %d students start at once, image %s, load average %s" % (
            opts.peak, opts.image, loadavg()), flush=True)
        for wave in ("first start (disks made)", "a later session (disks there)"):
            start_wave(hub, users, wave)
            for user in users:
                user.stop()
            wait_for(lambda: not any(user.server_state() for user in users), 300, 1.0)
    return 0


def start_wave(hub: LocalHub, users: List[HubUser], wave: str) -> None:
    """Every user's Start at once; when each JupyterLab answered, and what the start-ups cost."""
    done: Dict[str, float] = {}
    errors: List[str] = []
    memory_max: Dict[str, float] = {}
    began = time.monotonic()
    hub_before = tree_cpu_s(hub.proc.pid)

    def one(user: HubUser) -> None:
        try:
            user.start(timeout=900)
            status, _ = user.open_server()
            if status != 200:
                raise RuntimeError("%s's JupyterLab -> %d" % (user.name, status))
            done[user.name] = time.monotonic() - began
        except Exception as err:  # reported with the figures
            errors.append("%s: %s" % (user.name, err))
    threads = [threading.Thread(target=one, args=(u,)) for u in users]
    for t in threads:
        t.start()
    cgroups: Dict[str, Cgroup] = {}
    loads = []
    while any(t.is_alive() for t in threads):
        loads.append(float(loadavg().split()[0]))
        for user in users:
            try:
                if user.name not in cgroups:
                    cgroups[user.name] = Cgroup(container_pid(container_name(user.name), PODMAN))
                memory_max[user.name] = max(memory_max.get(user.name, 0.0), cgroups[user.name].memory_bytes() / MIB)
            except (RuntimeError, OSError):
                continue
        time.sleep(1.0)
    hub_cpu = tree_cpu_s(hub.proc.pid) - hub_before
    startup_cpu = [cgroups[n].cpu_s() for n in done if n in cgroups]
    times = sorted(done.values())
    if times:
        print("hub_bench --peak, %s: %d of %d servers ready (JupyterLab answering): first %.1f s, median %.1f s, "
              "last %.1f s -> %.1f servers started a minute" % (
                  wave, len(done), len(users), times[0], statistics.median(times), times[-1],
                  60.0 * len(done) / times[-1]))
    if startup_cpu:
        print("hub_bench --peak, %s: start-up CPU per student %.1f s (median; the cgroup's since its creation), "
              "%.0f s all together, the hub %.0f CPU s; memory at its highest during start-up %.0f MiB median, "
              "%.0f MiB most (file pages left out); load average during the burst %.1f-%.1f, now %s" % (
                  wave, statistics.median(startup_cpu), sum(startup_cpu), hub_cpu,
                  statistics.median(memory_max.values()), max(memory_max.values()), min(loads or [0]),
                  max(loads or [0]), loadavg()), flush=True)
    for err in errors:
        print("hub_bench --peak, %s: failed: %s" % (wave, err), flush=True)


def sweep(opts: argparse.Namespace) -> int:
    names = ["s%02d" % i for i in range(1, opts.max + 1)]
    students: List[Student] = []
    rows = []
    best = 0
    with scratch_hubs([(opts.image, names)]) as (hub,), closing(students):
        print("hub_bench: hub at %s, image %s, load average %s" % (hub.url, opts.image, loadavg()), flush=True)
        handed_out = passwords.handed_out(str(hub.data))  # the initial password the hub gave each student
        traffic: Optional[PageTraffic] = None
        while len(students) < opts.max:
            for name in names[len(students):len(students) + opts.step]:
                if traffic is None:  # the first student's page, in a real browser, shows what a page asks
                    first = Student(hub, name, handed_out[name])
                    first.move_turtle()
                    traffic = PageTraffic.record(hub, first, opts.record)
                    print("hub_bench: the lab page's traffic, %s" % traffic, flush=True)
                    first.page = LabPage(first.user, traffic)
                    students.append(first)
                    continue
                students.append(Student(hub, name, handed_out[name], traffic))
                if len(students) == 1:
                    print("hub_bench: spawn of one server (nothing else running): %.1f s" % students[0].spawn_s,
                          flush=True)
            n = len(students)
            meters = [s.meter(hub) for s in students]
            settle(meters)
            cost = windows(meters, opts.steady_window)
            frames_before = [s.page.frames for s in students]
            began = time.monotonic()
            measured = rates(students, opts.window)
            page_rates = [(s.page.frames - f) / (time.monotonic() - began) for s, f in zip(students, frames_before)]
            hub_home = latency(students[0].user, "/hub/home")
            server = latency(students[-1].user, "/user/%s/api/status" % students[-1].user.name)
            slowest = min(r for r, _ in measured)
            gap = max(g for _, g in measured)
            per_student = statistics.mean(w.memory_mib for w in cost)
            cpu = statistics.mean(w.cpu_pct for w in cost)
            ok = slowest >= MIN_RATE_HZ and max(hub_home[1], server[1]) <= MAX_LATENCY_S
            if ok and all(r[3] for r in rows):  # the last N before the first miss
                best = n
            row = ("N=%2d  pose rate slowest %.1f Hz, median %.1f, %d under %.0f (longest gap %.0f ms)  steady memory/student %.0f MiB (total %.0f)  "
                   "steady CPU/student %.1f%% (most %.1f%%; hub %.1f%%)  page messages/s slowest %.0f  "
                   "/hub/home median %.0f ms worst %.0f ms  server API median %.0f ms worst %.0f ms  spawn %.1f s  "
                   "load %s  %s" % (n, slowest, statistics.median(r for r, _ in measured),
                                    sum(r < MIN_RATE_HZ for r, _ in measured), MIN_RATE_HZ, gap, per_student, sum(w.memory_mib for w in cost), cpu,
                                    max(w.cpu_pct for w in cost), cost[0].hub_cpu_pct, min(page_rates),
                                    1000 * hub_home[0], 1000 * hub_home[1], 1000 * server[0], 1000 * server[1],
                                    students[-1].spawn_s, cost[0].load, "ok" if ok else "OVER"))
            rows.append((n, per_student, slowest, ok, cpu))
            print(row, flush=True)
            if not ok and not opts.keep_going:
                break
        print("hub_bench: largest N with every turtlesim >= %.0f Hz and the hub within %.0f s: %d (this machine: "
              "2 cores shared with other work; load average %s)" % (MIN_RATE_HZ, MAX_LATENCY_S, best, loadavg()))
        if rows:
            per_student = max(r[1] for r in rows)
            cores_per_student = max(r[4] for r in rows) / 100.0
            need_cores, need_gib = CLASS * cores_per_student, CLASS * per_student / 1024
            print("hub_bench: a class of %d, steady (turtlesim moving, the lab page open), from these figures: %.0f MiB "
                  "and %.3f cores a student (the most measured at any N) -> %.0f GiB and %.1f cores with everyone on "
                  "at once; the start-up peak is --peak's" % (CLASS, per_student, cores_per_student, need_gib,
                                                               need_cores))
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--image", default="localhost/ros-course")
    parser.add_argument("--max", type=int, default=12, help="students at most")
    parser.add_argument("--step", type=int, default=2, help="students added at each level")
    parser.add_argument("--window", type=float, default=10.0, help="seconds poses are counted")
    parser.add_argument("--steady-window", type=float, default=30.0,
                        help="seconds of each steady-state window (the cgroups' counters)")
    parser.add_argument("--steady", action="store_true",
                        help="one student per image through the four states, by process, instead of the sweep")
    parser.add_argument("--before-image", help="with --steady: a second image measured side by side")
    parser.add_argument("--keep-going", action="store_true",
                        help="the sweep goes on to --max past a level that misses a bar (the largest N printed is "
                             "still the last before the first miss)")
    parser.add_argument("--record", type=float, default=20.0,
                        help="seconds the lab page's traffic is recorded in chromium (the sweep)")
    parser.add_argument("--peak", type=int, default=0, help="K students starting at once, instead of the sweep")
    opts = parser.parse_args()
    if os.geteuid() != 0:
        print("hub_bench: run it as root (podman)", file=sys.stderr)
        return 2
    if opts.steady:
        return steady(opts)
    if opts.peak:
        return peak(opts)
    return sweep(opts)


if __name__ == "__main__":
    sys.exit(main())
