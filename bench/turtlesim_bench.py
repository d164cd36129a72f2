#!/usr/bin/env python3
"""turtlesim start-up, and turtlesim under load: N turtles all moving and drawing.

Start-up: from launching turtlesim_node to /spawn, by each way a student starts it (rosrun,
the executable itself, roslaunch), >= 10 runs each, interleaved so that load on the machine
hits every way alike. Two times per run: /spawn available (the probe rospy.wait_for_service
makes, polled every 10 ms instead of its 0.3 s) and a first /spawn call answered. Printed as
median and p90 against upstream C++'s 0.32 s; the target is 0.45 s.

Load: for N = 1, 20, 50 (or the N given), with every pose subscribed and with none, the CPU%
of one core used by the turtlesim process, the median of ROUNDS runs; with the poses
subscribed also the achieved pose rate per turtle (mean and worst) and the jitter a subscriber
sees (std dev and p99 of the gap between poses, against the 16 ms tick). When the upstream
C++ turtlesim_node is built beside it ($UPSTREAM_TURTLESIM, default
/tmp/upstream_ws/devel/lib/turtlesim/turtlesim_node: ros_tutorials' turtlesim built by hand in
a temporary catkin workspace, see docs/turtlesim_performance.md), every run of ours is paired
with one of upstream's under the same load and the table gives the ratio ours / upstream.
Target: <= 1.00x everywhere.

    python3 bench/turtlesim_bench.py [N ...]            # start-up, then load for N turtles
    python3 bench/turtlesim_bench.py --load [N ...]     # load only
    python3 bench/turtlesim_bench.py --startup [RUNS]   # start-up only
    python3 bench/turtlesim_bench.py --one N SUB [ours|upstream]   # one run, as JSON

ROUNDS (default 3) sets the runs per cell.
"""
from __future__ import annotations

import json
import math
import os
import socket
import statistics
import subprocess
import sys
import time
from pathlib import Path

from course_testkit.benchmarks import cpu_seconds, private_master

UPSTREAM_DEFAULT = "/tmp/upstream_ws/devel/lib/turtlesim/turtlesim_node"
LOAD_COUNTS = (1, 20, 50)
UPSTREAM_STARTUP_S = 0.32
STARTUP_TARGET_S = 0.45
STARTUP_RUNS = 12
STARTUP_POLL_S = 0.01
LAUNCH_PATHS = ("rosrun", "executable", "roslaunch")
WINDOW_S = 10.0
WARMUP_S = 2.0


def upstream_binary() -> str:
    """The upstream C++ turtlesim_node built beside us, or "" when there is none."""
    path = os.environ.get("UPSTREAM_TURTLESIM", UPSTREAM_DEFAULT)
    return path if os.access(path, os.X_OK) else ""


def sim_command(which: str, ros) -> tuple:
    """(command, env) starting our turtlesim or upstream's; upstream finds its own turtle images
    through the package path of the workspace it was built in."""
    if which == "ours":
        return ["rosrun", "turtlesim", "turtlesim_node"], None
    binary = upstream_binary()
    src = Path(binary).resolve().parents[3] / "src"
    env = dict(ros.env, ROS_PACKAGE_PATH="%s:%s" % (src, ros.env.get("ROS_PACKAGE_PATH", "")))
    return [binary], env


def run(n: int, subscribe: bool, which: str = "ours") -> dict:
    import rospy
    from geometry_msgs.msg import Twist

    from turtlesim.msg import Pose
    from turtlesim.srv import SetPen, Spawn

    with private_master() as ros:
        rospy.init_node("turtlesim_bench", anonymous=True, disable_signals=True)
        command, env = sim_command(which, ros)
        sim = ros.start(command, "turtlesim", env=env)
        rospy.wait_for_service("/spawn", 30)
        names = ["turtle1"]
        spawn = rospy.ServiceProxy("/spawn", Spawn)
        for i in range(1, n):
            names.append(spawn(1.0 + (i % 10) * 1.0, 1.0 + (i // 10) * 2.0, 0.0, "").name)
        for i, name in enumerate(names):
            rospy.wait_for_service("/%s/set_pen" % name, 10)
            rospy.ServiceProxy("/%s/set_pen" % name, SetPen)((40 * i) % 256, 200, (90 * i) % 256, 2, 0)
        arrivals = {name: [] for name in names}
        subs = [rospy.Subscriber("/%s/pose" % name, Pose, lambda _m, a=arrivals[name]: a.append(time.monotonic()),
                                 queue_size=100) for name in names] if subscribe else []
        pubs = [rospy.Publisher("/%s/cmd_vel" % name, Twist, queue_size=1) for name in names]
        deadline = time.monotonic() + 20
        while any(p.get_num_connections() == 0 for p in pubs) and time.monotonic() < deadline:
            time.sleep(0.01)
        twist = Twist()
        twist.linear.x, twist.angular.z = 1.0, 1.0  # circles of 1 m radius: moving and drawing
        start = time.monotonic()
        cpu_start = None
        while time.monotonic() - start < WARMUP_S + WINDOW_S:
            if cpu_start is None and time.monotonic() - start >= WARMUP_S:
                cpu_start, wall_start = cpu_seconds(sim.proc.pid), time.monotonic()
            for pub in pubs:
                pub.publish(twist)
            time.sleep(0.1)
        wall = time.monotonic() - wall_start
        cpu = 100.0 * (cpu_seconds(sim.proc.pid) - cpu_start) / wall
        rospy.signal_shutdown("bench done")
    result = {"n": n, "which": which, "cpu": cpu}
    if subscribe:
        rates, gaps = [], []
        for stamps in arrivals.values():
            window = [t for t in stamps if wall_start <= t <= wall_start + WINDOW_S]
            rates.append((len(window) - 1) / (window[-1] - window[0]) if len(window) > 1 else 0.0)
            gaps.extend(b - a for a, b in zip(window, window[1:]))
        gaps.sort()
        result.update(rate_mean=statistics.mean(rates), rate_min=min(rates),
                      jitter_ms=1000 * statistics.pstdev(gaps),
                      p99_gap_ms=1000 * gaps[min(len(gaps) - 1, int(math.ceil(0.99 * len(gaps))) - 1)])
    return result


def spawn_probe(master, caller_id: str) -> bool:
    """What rospy.wait_for_service checks: /spawn is registered and its server takes a connection."""
    import rosgraph.network
    try:
        code, _msg, uri = master.lookupService(caller_id, "/spawn")
    except OSError:
        return False
    if code != 1:
        return False
    host, port = uri[len("rosrpc://"):].rsplit(":", 1)
    try:
        with socket.create_connection((host, int(port)), timeout=2.0) as s:
            rosgraph.network.write_ros_handshake_header(
                s, {"probe": "1", "md5sum": "*", "callerid": caller_id, "service": "/spawn"})
        return True
    except OSError:
        return False


def launch_command(path: str, scratch: Path) -> list:
    from course_checks.nodes import find_executable
    if path == "rosrun":
        return ["rosrun", "turtlesim", "turtlesim_node"]
    if path == "executable":
        return [find_executable("turtlesim", "turtlesim_node")]
    launch = scratch / "turtlesim_only.launch"
    launch.write_text('<launch><node pkg="turtlesim" type="turtlesim_node" name="turtlesim"/></launch>\n')
    return ["roslaunch", str(launch)]


def startup_runs(runs: int) -> dict:
    """Launch-to-/spawn times per launch path: {path: {"available": [s...], "answered": [s...]}}."""
    import rospy
    from xmlrpc.client import ServerProxy

    from turtlesim.srv import Spawn

    times = {path: {"available": [], "answered": []} for path in LAUNCH_PATHS}
    with private_master() as ros:
        rospy.init_node("turtlesim_startup_bench", anonymous=True, disable_signals=True)
        caller_id = rospy.get_name()
        master = ServerProxy(os.environ["ROS_MASTER_URI"])
        commands = {path: launch_command(path, ros.home) for path in LAUNCH_PATHS}
        for run_index in range(runs):
            for path in LAUNCH_PATHS:
                launched = time.monotonic()
                sim = ros.start(commands[path], "%s-%d" % (path, run_index))
                while not spawn_probe(master, caller_id):
                    if time.monotonic() - launched > 30 or not sim.running():
                        raise RuntimeError("%s: /spawn never came up (see %s)" % (path, ros.home))
                    time.sleep(STARTUP_POLL_S)
                available = time.monotonic() - launched
                rospy.ServiceProxy("/spawn", Spawn)(1.0, 1.0, 0.0, "")
                answered = time.monotonic() - launched
                times[path]["available"].append(available)
                times[path]["answered"].append(answered)
                ros.stop_node(sim)
                deadline = time.monotonic() + 10  # the next run must not find this one's /spawn
                while spawn_probe(master, caller_id) and time.monotonic() < deadline:
                    time.sleep(STARTUP_POLL_S)
        rospy.signal_shutdown("bench done")
    return times


def median_p90(values: list) -> tuple:
    ordered = sorted(values)
    return statistics.median(ordered), ordered[max(0, math.ceil(0.9 * len(ordered)) - 1)]


def print_startup(times: dict) -> None:
    runs = len(next(iter(times.values()))["available"])
    print("start-up, launch to /spawn: median and p90 of %d runs per path (upstream C++: %.2f s, target <= %.2f s; "
          "load average %.1f on %d cores)" % (runs, UPSTREAM_STARTUP_S, STARTUP_TARGET_S, os.getloadavg()[0],
                                             os.cpu_count()))
    print("%-11s  %-30s  %-30s  %s" % ("launch", "/spawn available: median, p90", "first /spawn answered",
                                      "target (p90)"))
    for path, got in times.items():
        cells = []
        for key in ("available", "answered"):
            med, p90 = median_p90(got[key])
            cells.append("%.3f s (%.2fx), %.3f s" % (med, med / UPSTREAM_STARTUP_S, p90))
        med, p90 = median_p90(got["available"])
        verdict = "met" if p90 <= STARTUP_TARGET_S else ("median only" if med <= STARTUP_TARGET_S else "missed")
        print("%-11s  %-30s  %-30s  %s" % (path, cells[0], cells[1], verdict))
    print("(Nx = median / upstream C++'s %.2f s)" % UPSTREAM_STARTUP_S)
    sys.stdout.flush()


def in_subprocess(*args: str):
    """Run this file with `args` in its own process (rospy allows one node per process); its JSON answer."""
    out = subprocess.run([sys.executable, __file__] + list(args),
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def measure(n: int, subscribe: bool, which: str = "ours") -> dict:
    return in_subprocess("--one", str(n), "1" if subscribe else "0", which)


def load_table(counts: list, rounds: int) -> None:
    """CPU per (N, subscribed) for ours, paired run by run with upstream's when it is built."""
    sims = ["ours"] + (["upstream"] if upstream_binary() else [])
    print("turtlesim under load: N turtles moving and drawing, %.0f s window after %.0f s, median of %d runs, "
          "CPU%% of one core (load average %.1f on %d cores)" % (WINDOW_S, WARMUP_S, rounds, os.getloadavg()[0],
                                                                 os.cpu_count()))
    if len(sims) == 1:
        print("(no upstream turtlesim_node at %s: set UPSTREAM_TURTLESIM to compare)"
              % os.environ.get("UPSTREAM_TURTLESIM", UPSTREAM_DEFAULT))
    print("| N | poses | ours CPU% | upstream CPU% | ratio | ours rate Hz (worst) | ours jitter ms (p99 gap) |"
          " upstream rate Hz (worst) | upstream jitter ms (p99 gap) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for n in counts:
        for subscribe in (True, False):
            runs = {which: [] for which in sims}
            for _ in range(rounds):
                for which in sims:
                    runs[which].append(measure(n, subscribe, which))
            cells = {}
            for which in sims:
                got = runs[which]
                cpu = statistics.median(r["cpu"] for r in got)
                timing = ("%.2f (%.2f)" % (statistics.median(r["rate_mean"] for r in got), min(r["rate_min"] for r in got))
                          if subscribe else "-")
                jitter = ("%.2f (%.1f)" % (statistics.median(r["jitter_ms"] for r in got),
                                           max(r["p99_gap_ms"] for r in got)) if subscribe else "-")
                cells[which] = (cpu, timing, jitter)
            ours = cells["ours"]
            up = cells.get("upstream")
            print("| %d | %s | %.2f | %s | %s | %s | %s | %s | %s |" % (
                n, "every pose subscribed" if subscribe else "unsubscribed", ours[0],
                "%.2f" % up[0] if up else "-", "**%.2fx**" % (ours[0] / up[0]) if up and up[0] > 0 else "-",
                ours[1], ours[2], up[1] if up else "-", up[2] if up else "-"))
            sys.stdout.flush()


def main() -> int:
    if sys.argv[1:2] == ["--one"]:
        print(json.dumps(run(int(sys.argv[2]), sys.argv[3] == "1", (sys.argv[4:5] or ["ours"])[0])))
        return 0
    if sys.argv[1:2] == ["--startup-runs"]:
        print(json.dumps(startup_runs(int(sys.argv[2]))))
        return 0
    if sys.argv[1:2] == ["--startup"]:
        print_startup(in_subprocess("--startup-runs", (sys.argv[2:3] or [str(STARTUP_RUNS)])[0]))
        return 0
    rounds = int(os.environ.get("ROUNDS", "3"))
    if sys.argv[1:2] == ["--load"]:
        load_table([int(a) for a in sys.argv[2:]] or list(LOAD_COUNTS), rounds)
        return 0
    print_startup(in_subprocess("--startup-runs", str(STARTUP_RUNS)))
    load_table([int(a) for a in sys.argv[1:]] or list(LOAD_COUNTS), rounds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
