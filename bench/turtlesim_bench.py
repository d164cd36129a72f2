#!/usr/bin/env python3
"""turtlesim under load: N turtles all moving and drawing.

For N = 1, 10, 20, 50 prints the achieved pose rate per turtle (mean and worst),
the tick jitter seen by a subscriber (std dev and p99 of the gap between poses,
against the 16 ms tick) and the CPU% of one core used by the turtlesim process,
with every pose subscribed and, for CPU, also with none subscribed (as the
upstream figure was taken). Targets: 62.5 Hz within 1% at N = 50; at N = 20 no
more than 2x the 7.4% of a core the upstream C++ turtlesim needs.
"""
from __future__ import annotations

import json
import math
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rosenv import cpu_seconds, private_master  # noqa: E402

UPSTREAM_CPU_20 = 7.4
UPSTREAM_STARTUP_S = 0.32
WINDOW_S = 10.0
WARMUP_S = 2.0


def run(n: int, subscribe: bool) -> dict:
    import rospy
    from geometry_msgs.msg import Twist

    from turtlesim.msg import Pose
    from turtlesim.srv import SetPen, Spawn

    with private_master() as procs:
        rospy.init_node("turtlesim_bench", anonymous=True, disable_signals=True)
        launched = time.monotonic()
        sim = procs.start(["rosrun", "turtlesim", "turtlesim_node"], "turtlesim")
        rospy.wait_for_service("/spawn", 30)
        startup = time.monotonic() - launched
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
        cpu = 100.0 * (cpu_seconds(sim.proc.pid) - cpu_start) / (time.monotonic() - wall_start)
        rospy.signal_shutdown("bench done")
    result = {"n": n, "cpu": cpu, "startup": startup}
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


def measure(n: int, subscribe: bool) -> dict:
    """One run in its own process: rospy allows one node per process."""
    out = subprocess.run([sys.executable, __file__, "--one", str(n), "1" if subscribe else "0"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> int:
    if sys.argv[1:2] == ["--one"]:
        print(json.dumps(run(int(sys.argv[2]), sys.argv[3] == "1")))
        return 0
    counts = [int(a) for a in sys.argv[1:]] or [1, 10, 20, 50]
    print("turtlesim benchmark: N turtles moving and drawing, %.0f s window, 62.5 Hz target" % WINDOW_S)
    print("%4s  %9s  %9s  %8s  %10s  %10s  %12s" % ("N", "rate Hz", "worst Hz", "rate %", "jitter ms",
                                                     "p99 gap ms", "CPU% (subs)"))
    rows = []
    for n in counts:
        r = measure(n, subscribe=True)
        rows.append(r)
        print("%4d  %9.2f  %9.2f  %7.2f%%  %10.2f  %10.2f  %11.1f%%" % (
            n, r["rate_mean"], r["rate_min"], 100 * r["rate_min"] / 62.5, r["jitter_ms"], r["p99_gap_ms"], r["cpu"]))
        sys.stdout.flush()
    startups = sorted(r["startup"] for r in rows)
    print("start-up, launch to /spawn available: median %.2f s over %d runs (upstream C++: %.2f s)"
          % (startups[len(startups) // 2], len(startups), UPSTREAM_STARTUP_S))
    print("CPU% of one core with nobody subscribed to the poses (as upstream was measured):")
    for n in counts:
        r = measure(n, subscribe=False)
        ratio = " = %.2fx upstream C++ (%.1f%%)" % (r["cpu"] / UPSTREAM_CPU_20, UPSTREAM_CPU_20) if n == 20 else ""
        print("%4d  %5.1f%%%s" % (n, r["cpu"], ratio))
    return 0


if __name__ == "__main__":
    sys.exit(main())
