#!/usr/bin/env python3
"""The student's workbench (`make jupyter`), measured: figures printed, nothing asserted.

- Start-up: from the command to a usable JupyterLab (its REST API answers and a new terminal runs
  a first command), median and worst of --runs; for a first start (the overlay ~/catkin_ws made
  and built) and for a start with the overlay already built (the image builds it), through
  `make jupyter` itself (--direct: the start-up command alone, without make). Target <= 10 s.
- Memory, PSS summed over every process of the workbench (course_sandbox.procs): idle (JupyterLab
  alone, after start-up); with one terminal open; with the lab page open (its own master,
  turtlesim, lab_view, roslab). Target idle <= 400 MiB.
- --frame-rate: the lab page's canvas updates per second as its websocket receives them (turtlesim's
  ~scene, subscribed as the page subscribes, while turtle1 drives a circle from Twists sent through
  the same websocket; 20.8 nominal), through JupyterLab's proxy (`<base>/roslab/websocket`,
  jupyter-server-proxy) and direct (lab_view's own port), alternately for --rounds rounds of
  --seconds each; both rates and their ratio. Target: through the proxy >= 90 % of direct.
- --desktop: memory with the desktop open (headless chromium on <base>/desktop/: TigerVNC, JWM, an
  xterm), then 004's demo with rviz on it, then the lab page on the student's master; and by program.

Run from a sourced workspace:
    python3 bench/workbench_bench.py [--runs 5] [--direct]
    python3 bench/workbench_bench.py --frame-rate [--seconds 10] [--rounds 3]
    python3 bench/workbench_bench.py --desktop
"""
from __future__ import annotations

import argparse
import asyncio
import json
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Dict, List, Optional, Sequence

from course_sandbox.procs import cmdline, proportional_bytes
from course_checks.isolation import pids_with_token
from course_checks.waiting import wait_for
from course_testkit.workbench import Workbench

ROOT = Path(__file__).resolve().parents[1]
TARGET_START_S = 10.0
TARGET_IDLE_MIB = 400.0
TARGET_PROXY_RATIO = 0.90
SCENE_TOPIC = "/turtlesim/scene"
CIRCLE = {"linear": {"x": 1.0, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.8}}
TWIST_PERIOD_S = 0.1
SETTLE_S = 3.0  # let JupyterLab's start-up work (extension loading, language-server scan) end


def workbench_mib(bench: Workbench) -> float:
    return sum(proportional_bytes(pid) or 0 for pid in pids_with_token(bench.run_token)) / 2 ** 20


def start_once(command: Optional[Sequence[str]], home: Optional[str]) -> float:
    """Seconds from the command to a terminal's first answer."""
    began = time.monotonic()
    with Workbench(home=home, command=command) as bench:
        with bench.terminal() as term:
            term.run("true")
        return time.monotonic() - began


def prepared_home() -> str:
    """A home whose overlay is built (as in the image)."""
    home = tempfile.mkdtemp(prefix="workbench-bench-")
    with Workbench(home=home):
        pass
    return home


def startup(runs: int, command: Optional[Sequence[str]]) -> None:
    how = " ".join(command) if command else "rosrun course_workbench workbench"
    first: List[float] = [start_once(command, None) for _ in range(runs)]
    home = prepared_home()
    try:
        again = [start_once(command, home) for _ in range(runs)]
    finally:
        shutil.rmtree(home, ignore_errors=True)
    for label, times in (("first start (overlay made and built)", first), ("overlay already built", again)):
        print("start-up, %s, `%s`: median %.2f s, worst %.2f s over %d (target <= %.0f s)"
              % (label, how, statistics.median(times), max(times), len(times), TARGET_START_S), flush=True)


def memory() -> None:
    with Workbench() as bench:
        time.sleep(SETTLE_S)  # a figure of the idle state: nothing to wait for but time itself
        print("memory, idle workbench (JupyterLab): %.0f MiB PSS (target <= %.0f MiB)"
              % (workbench_mib(bench), TARGET_IDLE_MIB), flush=True)
        with bench.terminal() as term:
            term.run("true")
            print("memory, with a terminal open: %.0f MiB PSS" % workbench_mib(bench), flush=True)
            assert bench.status("/roslab/") == 200
            wait_for(lambda: bench.processes("turtlesim"), 30)
            time.sleep(SETTLE_S)
            print("memory, with the lab page (its master, turtlesim at 30 fps, lab_view, roslab) and the terminal: "
                  "%.0f MiB PSS" % workbench_mib(bench), flush=True)


def program_mib(bench: Workbench) -> Dict[str, float]:
    """PSS (MiB) of the workbench's processes by program: the executable's name, or for python3 and
    perl the script's."""
    found: Dict[str, float] = {}
    for pid in pids_with_token(bench.run_token):
        words = cmdline(pid)
        if not words:  # gone
            continue
        names = [os.path.basename(w) for w in words[:3] if not w.startswith("-")]
        name = next((n for n in names[1:] if names[0].startswith(("python", "perl"))), None) \
            or (names[0] if names else "?")
        found[name] = found.get(name, 0.0) + (proportional_bytes(pid) or 0) / 2 ** 20
    return found


def desktop_memory() -> None:
    """Memory with the desktop (<base>/desktop/) open in headless chromium: TigerVNC's X server,
    JWM, the desktop's xterm; then 004's demo with rviz on it (the student's master, turtlesim's
    window, the broadcasters, rviz), then the lab page following that master. Chromium is not the
    workbench's and is not counted."""
    from course_testkit.browser import chromium
    from course_testkit.xwindows import largest_titled, x_windows

    with Workbench() as bench, chromium(window=(1800, 1500)) as browser:
        time.sleep(SETTLE_S)
        print("memory, idle workbench (JupyterLab): %.0f MiB PSS" % workbench_mib(bench), flush=True)
        browser.get("%s/desktop/?token=%s" % (bench.url, bench.token))
        connected = wait_for(lambda: browser.execute_script(
            "const s = document.getElementById('status'); return s && s.textContent") == "Connected", 60, 0.2)
        assert connected, "the desktop did not connect"
        wait_for(lambda: bench.processes("xterm") and bench.processes("jwm"), 30)
        time.sleep(SETTLE_S)
        print("memory, with the desktop open (TigerVNC, JWM, its xterm): %.0f MiB PSS" % workbench_mib(bench),
              flush=True)
        with bench.terminal() as term:
            display = term.run('echo "[$DISPLAY]"')[1].split("[", 1)[1].split("]", 1)[0]
            term.run("roslaunch turtle_tf2 turtle_tf2_demo.launch rviz:=true > ~/demo.log 2>&1 &")
            xauthority = os.path.join(bench.home, ".Xauthority")
            shown = wait_for(lambda: all(largest_titled(x_windows(display, xauthority), t) for t in ("TurtleSim", "RViz")),
                             120, 0.5)
            assert shown, "turtlesim's and rviz's windows did not show on %s" % display
            time.sleep(2 * SETTLE_S)  # rviz loads its plugins and draws
            print("memory, with 004's demo on the desktop (its master, turtlesim's window, two broadcasters, the "
                  "follower, rviz) and a terminal: %.0f MiB PSS" % workbench_mib(bench), flush=True)
            assert bench.status("/roslab/") == 200
            wait_for(bench.lab_view_port, 60)
            wait_for(lambda: "/workbench_lab_view" in term.run("rosnode list 2>&1")[1], 60, 0.5)
            time.sleep(SETTLE_S)
            print("memory, and the lab page on the student's master (roslab, lab_view): %.0f MiB PSS"
                  % workbench_mib(bench), flush=True)
            ranked = sorted(program_mib(bench).items(), key=lambda item: -item[1])
            print("memory by program: %s" % ", ".join("%s %.0f" % item for item in ranked if item[1] >= 1), flush=True)
            term.run("kill %1; wait")


def scene_rate(ws_url: str, seconds: float) -> float:
    """~scene updates a second through the websocket at `ws_url` while the same websocket drives
    turtle1 in a circle, counted for `seconds` from the first update."""
    import tornado.websocket

    async def count() -> float:
        socket = await tornado.websocket.websocket_connect(ws_url, connect_timeout=30)
        for request in ({"op": "advertise", "topic": "/turtle1/cmd_vel", "type": "geometry_msgs/Twist"},
                        {"op": "subscribe", "id": "scene", "topic": SCENE_TOPIC, "type": "std_msgs/String",
                         "queue_length": 100}):
            await socket.write_message(json.dumps(request))

        async def drive() -> None:
            while True:
                await socket.write_message(json.dumps({"op": "publish", "topic": "/turtle1/cmd_vel", "msg": CIRCLE}))
                await asyncio.sleep(TWIST_PERIOD_S)
        driver = asyncio.ensure_future(drive())
        updates, began = 0, None
        try:
            while began is None or time.monotonic() < began + seconds:
                left = 30.0 if began is None else began + seconds - time.monotonic()
                try:
                    message = await asyncio.wait_for(socket.read_message(), max(left, 0.001))
                except asyncio.TimeoutError:
                    if began is None:
                        raise ConnectionError("no update of %s through %s" % (SCENE_TOPIC, ws_url.split("?")[0]))
                    break
                if message is None:
                    raise ConnectionError("the websocket at %s closed" % ws_url.split("?")[0])
                if isinstance(message, str) and json.loads(message).get("topic") == SCENE_TOPIC:
                    if began is None:
                        began = time.monotonic()  # the clock starts at the first update
                    else:
                        updates += 1
        finally:
            driver.cancel()
            socket.close()
        return updates / seconds
    return asyncio.run(count())


def frame_rates(seconds: float, rounds: int) -> None:
    with Workbench() as bench:
        assert bench.status("/roslab/") == 200  # roslab starts: its master, turtlesim, lab_view
        port = wait_for(bench.lab_view_port, 30)
        ways = {"direct (lab_view's port)": "ws://127.0.0.1:%d/websocket?token=%s" % (port, bench.token),
                "through the proxy (/roslab/websocket)": "ws://127.0.0.1:%d/roslab/websocket?token=%s"
                % (bench.port, bench.token)}
        rates: Dict[str, List[float]] = {way: [] for way in ways}
        for _ in range(rounds):  # alternately, so that the machine's other load falls on both
            for way, url in ways.items():
                rates[way].append(scene_rate(url, seconds))
        for way, found in rates.items():
            print("canvas updates, %s: median %.1f a second (%s)" % (way, statistics.median(found),
                                                           ", ".join("%.1f" % r for r in found)), flush=True)
        direct, proxied = (statistics.median(found) for found in rates.values())
        print("canvas updates through the proxy / direct: %.0f %% (target >= %.0f %%), %d rounds of %.0f s each way"
              % (100 * proxied / direct, 100 * TARGET_PROXY_RATIO, rounds, seconds), flush=True)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--direct", action="store_true", help="the start-up command alone, without make")
    parser.add_argument("--frame-rate", action="store_true", help="only the lab page's frame rate through the "
                        "proxy against direct")
    parser.add_argument("--seconds", type=float, default=10.0, help="--frame-rate: each measurement's length")
    parser.add_argument("--rounds", type=int, default=3, help="--frame-rate: measurements each way")
    parser.add_argument("--desktop", action="store_true", help="only the memory with the desktop, turtlesim, rviz "
                        "and the lab page")
    args = parser.parse_args(argv)
    if args.desktop:
        desktop_memory()
        return 0
    if args.frame_rate:
        frame_rates(args.seconds, args.rounds)
        return 0
    command = None if args.direct else ["make", "--no-print-directory", "-C", str(ROOT), "jupyter"]
    startup(args.runs, command)
    memory()
    return 0


if __name__ == "__main__":
    sys.exit(main())
