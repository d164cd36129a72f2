#!/usr/bin/env python3
"""What course_env's usercustomize saves each rospy process (issue 23: rospy without numpy and pyparsing).

    python3 bench/python_startup_bench.py [--runs 7]

Run from a sourced workspace. Each case starts RUNS fresh processes with the hook (this
environment) and RUNS without it (the same environment less course_env's python_startup folder on
PYTHONPATH), alternating; of each process once it is ready: RssAnon (/proc/PID/status), CPU time
(/proc/PID/schedstat: nanoseconds on a CPU, user and system, not rounded to clock ticks) and the wall
time from its start; the median of the runs.

- `python3 -c pass`, `import rospy`, `import roslaunch`, `import rostopic`: /usr/bin/python3 (the
  interpreter of the nodes' and tools' #! lines) prints a line once the import is done and waits;
- `rostopic pub -r 10 /bench_startup std_msgs/String` against a private roscore on a free port:
  ready once the master lists it as the topic's publisher; stopped before the next run.

Also usercustomize's own import time (`-X importtime`, self, median), and the load average before
and after (other work on the machine shares the 2 cores).
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from typing import Callable, Dict, List, NamedTuple

from course_testkit.benchmarks import private_master, rss_anon_kib

from course_checks.waiting import wait_for
from course_sandbox.env_paths import drop_entries
from course_testkit.master import PrivateMaster, system_state

PYTHON = "/usr/bin/python3"
STARTUP_FOLDER = os.path.join("lib", "course_env", "python_startup")
IMPORTS = {"python3 -c pass": "", "import rospy": "import rospy", "import roslaunch": "import roslaunch",
           "import rostopic": "import rostopic"}
READY = "import sys\n%s\nsys.stdout.write('ready\\n')\nsys.stdout.flush()\nsys.stdin.read()\n"
TOPIC = "/bench_startup"
PUB_TIMEOUT_S = 60.0


class Sample(NamedTuple):
    rss_anon_mib: float
    cpu_s: float
    wall_s: float


def cpu_seconds(pid: int) -> float:
    """Time the process spent on a CPU so far (the first field of /proc/PID/schedstat, in ns)."""
    with open("/proc/%d/schedstat" % pid) as f:
        return int(f.read().split()[0]) / 1e9


def sample(pid: int, started: float) -> Sample:
    return Sample(rss_anon_kib(pid) / 1024.0, cpu_seconds(pid), time.perf_counter() - started)


def without_hook(env: Dict[str, str]) -> Dict[str, str]:
    return drop_entries(env, lambda p: p.rstrip("/").endswith(STARTUP_FOLDER))


def run_import(env: Dict[str, str], statement: str) -> Sample:
    started = time.perf_counter()
    proc = subprocess.Popen([PYTHON, "-c", READY % statement], env=env, stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, text=True)
    try:
        if proc.stdout.readline().strip() != "ready":
            raise RuntimeError("%r did not start: exit code %s" % (statement, proc.wait()))
        return sample(proc.pid, started)
    finally:
        proc.stdin.close()
        proc.wait(timeout=30)


def publishers(uri: str) -> List[str]:
    state = system_state(uri) or [[]]
    return next((nodes for topic, nodes in state[0] if topic == TOPIC), [])


def run_pub(master: PrivateMaster, env: Dict[str, str]) -> Sample:
    started = time.perf_counter()
    node = master.start(["rostopic", "pub", "-r", "10", TOPIC, "std_msgs/String", "data: bench"], "pub", env=env)
    try:
        if not wait_for(lambda: publishers(master.uri), PUB_TIMEOUT_S, 0.01):
            raise RuntimeError("rostopic pub did not register within %.0f s: %s" % (PUB_TIMEOUT_S, node.output()))
        return sample(node.proc.pid, started)
    finally:
        master.stop_node(node)
        wait_for(lambda: not publishers(master.uri), PUB_TIMEOUT_S, 0.01)


def medians(samples: List[Sample]) -> Sample:
    return Sample(*(statistics.median(values) for values in zip(*samples)))


def compare(name: str, runs: int, run: Callable[[Dict[str, str]], Sample], hooked: Dict[str, str]) -> None:
    """`run` in `hooked` and in it less the hook, alternately, `runs` times each; one line of medians."""
    with_hook: List[Sample] = []
    without: List[Sample] = []
    for _ in range(runs):
        with_hook.append(run(hooked))
        without.append(run(without_hook(hooked)))
    a, b = medians(with_hook), medians(without)
    print("%-20s %6.2f %6.2f %5.2f   %6.3f %6.3f %6.3f   %6.3f %6.3f" % (
        name, a.rss_anon_mib, b.rss_anon_mib, b.rss_anon_mib - a.rss_anon_mib,
        a.cpu_s, b.cpu_s, b.cpu_s - a.cpu_s, a.wall_s, b.wall_s), flush=True)


def usercustomize_import_us(env: Dict[str, str], runs: int) -> float:
    """usercustomize's own import time (self, microseconds), median of `runs` starts."""
    times = []
    for _ in range(runs):
        err = subprocess.run([PYTHON, "-X", "importtime", "-c", "pass"], env=env, capture_output=True,
                             text=True, check=True).stderr
        line = next(line for line in err.splitlines() if line.split("|")[-1].strip() == "usercustomize")
        times.append(int(line.split(":")[1].split("|")[0]))
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=7, help="processes per case and arm (default 7)")
    args = parser.parse_args()
    hooked = dict(os.environ)
    hooked.pop("PYTHONNOUSERSITE", None)
    if hooked == without_hook(hooked):
        sys.exit("course_env's python_startup folder is not on PYTHONPATH: source catkin_ws/devel/setup.bash")
    print("load average before: %.2f %.2f %.2f" % os.getloadavg())
    print("usercustomize's own import: %.0f us (median of %d starts, -X importtime self)"
          % (usercustomize_import_us(hooked, args.runs), args.runs))
    print("median of %d runs each    RssAnon MiB: hook  none  saved   CPU s: hook   none  saved   wall s: hook  none"
          % args.runs)
    for name, statement in IMPORTS.items():
        compare(name, args.runs, lambda env, s=statement: run_import(env, s), hooked)
    with private_master(rosout=True) as master:
        compare("rostopic pub", args.runs, lambda env: run_pub(master, env), master.env)
    print("load average after: %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    main()
