#!/usr/bin/env python3
"""The class's hub on this machine, measured: figures printed, nothing asserted (root, podman).

N students, added --step at a time: each logs in over HTTP, starts their server, runs roscore, a
turtlesim and a steady `rostopic pub -r 10` of a turning Twist in a terminal (the turtle drives
in circles), and has the lab page open (its page, then its rosbridge websocket through the hub
subscribed to the canvas as JPEG and to /rosout, as the page's canvas and console panels do, read
all the time; /api/graph every 2 s as the graph panel does). At each N:

- turtlesim's tick rate: every student's /turtle1/pose counted for --window seconds at once, by
  a subscriber in their own container (rospy, in a terminal); the slowest student's rate, and the
  longest gap between two poses;
- memory: each container's memory use (podman stats), the mean per student;
- the lab pages' messages per second (the canvas frames and /rosout lines each page received
  during the count: the slowest page), to show the pages were live;
- the hub's page latency: GET /hub/home and GET /user/<name>/api/status (through the proxy), 20
  of each, median and worst;
- the machine's load average.

The largest N at which every turtlesim holds >= 60 Hz and the hub answers within 1 s is printed,
with the spawn time of one server (the first, nothing else running) and what a class of 300
needs under Kubernetes, derived from these figures.

    sudo python3 bench/hub_bench.py --image localhost/ros-course-hub --max 12 --step 2

Run from a sourced workspace (course_testkit). This machine: 2 cores shared with other work,
so the figures are a floor, not what a dedicated node gives.
"""
from __future__ import annotations

import argparse
import asyncio
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
from pathlib import Path
from typing import Dict, List, Optional, Tuple

from tornado.websocket import websocket_connect

from course_hub import passwords
from course_testkit.hub import HubUser, LocalHub

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


class LabPage:
    """The lab page of one student, open: its websocket through the hub read all the time."""

    def __init__(self, user: HubUser) -> None:
        self.user = user
        self.frames = 0
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()
        status, _, _ = user.http("GET", "/user/%s/roslab/" % user.name)
        if status != 200:
            raise RuntimeError("%s's lab page -> %d" % (user.name, status))
        self.socket = asyncio.run_coroutine_threadsafe(self._open(), self.loop).result(60)
        asyncio.run_coroutine_threadsafe(self._read(), self.loop)
        self.graph_stop = threading.Event()
        threading.Thread(target=self._graph, daemon=True).start()

    async def _open(self):
        request = self.user.websocket_request("/roslab/websocket")
        socket = await websocket_connect(request)
        for message in ({"op": "subscribe", "id": "canvas", "topic": "/turtlesim/image", "type": "sensor_msgs/Image",
                         "compression": "jpeg", "queue_length": 1},
                        {"op": "subscribe", "id": "console", "topic": "/rosout", "type": "rosgraph_msgs/Log"}):
            await socket.write_message(json.dumps(message))
        return socket

    async def _read(self) -> None:
        while await self.socket.read_message() is not None:
            self.frames += 1

    def _graph(self) -> None:
        while not self.graph_stop.wait(2.0):
            self.user.http("GET", "/user/%s/roslab/api/graph" % self.user.name)

    def close(self) -> None:
        self.graph_stop.set()
        self.loop.call_soon_threadsafe(self.socket.close)
        self.loop.call_soon_threadsafe(self.loop.stop)


class Student:
    def __init__(self, hub: LocalHub, name: str, password: str) -> None:
        self.user = HubUser(hub.url, name, password)
        self.user.login()
        self.spawn_s = self.user.start()
        status, url = self.user.open_server()  # JupyterLab's page: the hub's OAuth, the server's cookies
        if status != 200:
            raise RuntimeError("%s's JupyterLab -> %d (%s)" % (name, status, url))
        self.term = self.user.terminal()
        self.user.write_file("pose_rate.py", POSE_RATE)
        code, said = self.term.run("(roscore > ~/roscore.log 2>&1 &) ; until rostopic list > /dev/null 2>&1; do "
                                   "sleep 0.2; done; (rosrun turtlesim turtlesim_node > ~/turtlesim.log 2>&1 &) ; "
                                   "until rostopic list | grep -q /turtle1/pose; do sleep 0.2; done; " + MOVE,
                                   timeout=180)
        if code != 0:
            raise RuntimeError("%s: %s" % (name, said))
        self.page = LabPage(self.user)

    def pose_rate(self, window: float) -> Tuple[float, float]:
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


def container_stats() -> Dict[str, Tuple[float, float]]:
    """{container: (memory MiB, CPU % of one core)} of the students' containers (podman stats)."""
    out = subprocess.run(PODMAN + ["stats", "--no-stream", "--format", "{{.Name}} {{.MemUsage}} {{.CPUPerc}}"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=False).stdout
    found = {}
    for line in out.splitlines():
        parts = line.split()
        if parts and parts[0].startswith("course-hub-"):
            found[parts[0]] = (_mib(parts[1]), float(parts[-1].rstrip("%") or 0))
    return found


def _mib(text: str) -> float:
    number = float(re.match(r"[\d.]+", text).group(0))
    unit = text[len(re.match(r"[\d.]+", text).group(0)):].lower()
    scale = {"b": 1 / 2 ** 20, "kb": 1000 / 2 ** 20, "kib": 1 / 1024, "mb": 1e6 / 2 ** 20, "mib": 1.0,
             "gb": 1e9 / 2 ** 20, "gib": 1024.0}
    return number * scale.get(unit, 1.0)


def latency(user: HubUser, path: str, count: int = 20) -> Tuple[float, float]:
    times = []
    for _ in range(count):
        began = time.monotonic()
        status, _, _ = user.http("GET", path)
        times.append(time.monotonic() - began if status == 200 else math.inf)
    return statistics.median(times), max(times)


def load() -> str:
    return " ".join(open("/proc/loadavg").read().split()[:3])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--image", default="localhost/ros-course")
    parser.add_argument("--max", type=int, default=12, help="students at most")
    parser.add_argument("--step", type=int, default=2, help="students added at each level")
    parser.add_argument("--window", type=float, default=10.0, help="seconds poses are counted")
    opts = parser.parse_args()
    if os.geteuid() != 0:
        print("hub_bench: run it as root (podman)", file=sys.stderr)
        return 2
    names = ["s%02d" % i for i in range(1, opts.max + 1)]
    work = Path(tempfile.mkdtemp(prefix="hub-bench-"))
    os.chmod(work, 0o755)
    hub = LocalHub(opts.image, work, names)
    students: List[Student] = []
    rows = []
    best = 0
    try:
        hub.start()
        print("hub_bench: hub at %s, image %s, load average %s" % (hub.url, opts.image, load()), flush=True)
        handed_out = passwords.handed_out(str(hub.data))  # the initial password the hub gave each student
        while len(students) < opts.max:
            for name in names[len(students):len(students) + opts.step]:
                students.append(Student(hub, name, handed_out[name]))
                if len(students) == 1:
                    print("hub_bench: spawn of one server (nothing else running): %.1f s" % students[0].spawn_s,
                          flush=True)
            n = len(students)
            frames_before = [s.page.frames for s in students]
            began = time.monotonic()
            measured = rates(students, opts.window)
            page_rates = [(s.page.frames - f) / (time.monotonic() - began) for s, f in zip(students, frames_before)]
            stats = container_stats()
            memory = {name: mib for name, (mib, _) in stats.items()}
            cpu = statistics.mean(pct for _, pct in stats.values()) if stats else float("nan")
            hub_home = latency(students[0].user, "/hub/home")
            server = latency(students[-1].user, "/user/%s/api/status" % students[-1].user.name)
            slowest = min(r for r, _ in measured)
            gap = max(g for _, g in measured)
            per_student = statistics.mean(memory.values()) if memory else float("nan")
            ok = slowest >= MIN_RATE_HZ and max(hub_home[1], server[1]) <= MAX_LATENCY_S
            if ok:
                best = n
            row = ("N=%2d  pose rate slowest %.1f Hz (longest gap %.0f ms)  memory/student %.0f MiB (total %.0f)  "
                   "CPU/student %.0f%%  page messages/s slowest %.0f  "
                   "/hub/home median %.0f ms worst %.0f ms  server API median %.0f ms worst %.0f ms  spawn %.1f s  "
                   "load %s  %s" % (n, slowest, gap, per_student, sum(memory.values()), cpu, min(page_rates),
                                    1000 * hub_home[0], 1000 * hub_home[1], 1000 * server[0], 1000 * server[1],
                                    students[-1].spawn_s, load(), "ok" if ok else "OVER"))
            rows.append((n, per_student, slowest, ok, cpu))
            print(row, flush=True)
            if not ok:
                break
        print("hub_bench: largest N with every turtlesim >= %.0f Hz and the hub within %.0f s: %d (this machine: "
              "2 cores shared with other work; load average %s)" % (MIN_RATE_HZ, MAX_LATENCY_S, best, load()))
        if rows:
            per_student = max(r[1] for r in rows)
            cores_per_student = max(r[4] for r in rows) / 100.0
            need_cores, need_gib = CLASS * cores_per_student, CLASS * per_student / 1024
            print("hub_bench: a class of %d under Kubernetes, from these figures: %.0f MiB and %.2f cores a student "
                  "(the most measured at any N) -> %.0f GiB and %.0f cores with everyone on at once; nodes of "
                  "8 cores / 32 GiB (28 GiB for pods): %d" % (
                      CLASS, per_student, cores_per_student, need_gib, need_cores,
                      math.ceil(max(need_cores / 8, need_gib / 28))))
    finally:
        for student in students:
            try:
                student.page.close()
                student.term.close()
            except Exception:
                pass
        hub.stop()
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
