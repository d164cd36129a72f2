"""What one student's lab costs once it has settled, process by process (issue 23, item 2).

    python3 bench/student_cost.py [--window 30] [--settle 5] [--before REV]

It starts what a student's lab page runs (as the workbench's roslab starts it: a master with
rosout, turtlesim, lab_view on its own port) from a checkout's solutions_ws, and measures three
states one after the other, each over a window after a settle time:

- idle: nothing running but those (turtlesim still, no page open);
- moving: + `rostopic pub -r 10 /turtle1/cmd_vel` driving turtle1 in a circle;
- page: + the lab page open in a headless chromium.

For each process: CPU as % of one core (utime + stime from /proc/PID/stat, the delta over the
window) and memory without page cache (RssAnon from /proc/PID/status), the student's total (the
browser is the student's own machine, shown apart), and the load average beside it (other work on
the machine shares the cores). `--before REV` builds REV in a git worktree under /tmp (once) and
measures it first, then this checkout, in the same run: before and after side by side.
Run from a sourced workspace (selenium and the browser helpers come from course_testkit).
"""
from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional, Tuple

from course_checks.isolation import free_port
from course_checks.waiting import wait_for
from course_sandbox import procs
from course_testkit.benchmarks import rss_anon_kib
from course_testkit.browser import chromium

ROOT = Path(__file__).resolve().parent.parent
STATES = ("idle", "moving", "page")
TWIST = "{linear: {x: 1.0}, angular: {z: 0.8}}"
IMAGE_RATE = 30  # what roslab gives its turtlesim (course_workbench.roslab.IMAGE_RATE before the cut)
TOKEN = "student-cost-bench"
TARGET_CPU_PERCENT = 5.0
TARGET_MIB = 200.0


def checkout_env(checkout: Path) -> Dict[str, str]:
    """The environment of `checkout`'s solutions_ws (sourced in bash), headless."""
    setup = checkout / "solutions_ws" / "devel" / "setup.bash"
    out = subprocess.run(["bash", "-c", "source %s && env -0" % setup], check=True, capture_output=True).stdout
    env = dict(item.split("=", 1) for item in out.decode().split("\0") if "=" in item)
    env["QT_QPA_PLATFORM"] = "offscreen"
    env.pop("DISPLAY", None)
    return env


def built_worktree(rev: str) -> Path:
    """REV checked out under /tmp and both workspaces built there (once)."""
    path = Path("/tmp/student-cost-%s" % rev)
    if not path.exists():
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(path), rev], check=True)
    if not (path / "solutions_ws" / "devel" / "setup.bash").exists():
        build = ("cd {p}/catkin_ws && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release"
                 " >/dev/null && source devel/setup.bash && cd {p}/solutions_ws && catkin_make"
                 " -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release >/dev/null").format(p=path)
        env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS", "CMAKE_PREFIX", "PYTHONPATH"))}
        subprocess.run(["bash", "-c", build], check=True, env=env)
    return path


def cpu_seconds(pid: int) -> float:
    use = procs.usage(pid)
    if use is None:
        raise ProcessLookupError(pid)
    return use.cpu_seconds


def label(pid: int) -> str:
    """A short name for a process: its node name or program."""
    try:
        with open("/proc/%d/cmdline" % pid, "rb") as f:
            argv = [a.decode(errors="replace") for a in f.read().split(b"\0") if a]
    except OSError:
        return "?"
    for arg in argv:
        if arg.startswith("__name:="):
            return arg.split("=", 1)[1]
    for arg in argv:
        base = os.path.basename(arg)
        if base in ("rosmaster", "rosout", "turtlesim_node", "lab_view", "rostopic", "roscore"):
            return base
    return os.path.basename(argv[0]) if argv else "?"


class Lab:
    """One checkout's student lab: master + rosout, turtlesim, lab_view, and later a publisher."""

    def __init__(self, checkout: Path) -> None:
        self.env = checkout_env(checkout)
        self.port = free_port()
        self.page_port = free_port()
        self.env["ROS_MASTER_URI"] = "http://localhost:%d" % self.port
        self.env["ROS_HOSTNAME"] = "localhost"
        self.env["LAB_VIEW_TOKEN"] = TOKEN
        self.procs: List[subprocess.Popen] = []

    def start(self, *argv: str) -> subprocess.Popen:
        proc = subprocess.Popen(list(argv), env=self.env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
        self.procs.append(proc)
        return proc

    def __enter__(self) -> "Lab":
        self.start("roscore", "-p", str(self.port))
        if not wait_for(lambda: self.rosnode_ok("/rosout"), 30):
            raise SystemExit("roscore did not start")
        self.start("rosrun", "turtlesim", "turtlesim_node", "_image_rate:=%d" % IMAGE_RATE)
        self.start("rosrun", "course_web", "lab_view", "--port", str(self.page_port), "--address", "127.0.0.1",
                   "__name:=workbench_lab_view")
        if not wait_for(lambda: self.rosnode_ok("/turtlesim") and self.rosnode_ok("/workbench_lab_view"), 60):
            raise SystemExit("turtlesim or lab_view did not start")
        return self

    def rosnode_ok(self, node: str) -> bool:
        return subprocess.run(["rosnode", "ping", "-c", "1", node], env=self.env, capture_output=True).returncode == 0

    def drive(self) -> None:
        self.start("rostopic", "pub", "-r", "10", "/turtle1/cmd_vel", "geometry_msgs/Twist", TWIST)

    def pids(self) -> List[int]:
        return [p for proc in self.procs if proc.poll() is None for p in [proc.pid] + procs.descendants(proc.pid)]

    def __exit__(self, *_exc) -> None:
        for proc in reversed(self.procs):
            try:
                os.killpg(proc.pid, signal.SIGINT)
                proc.wait(10)
            except (ProcessLookupError, subprocess.TimeoutExpired):
                pass
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait()


BROWSER = "chromium"


def measure(pids: List[int], window: float, browser: Tuple[int, ...] = ()) -> Tuple[Dict[str, Tuple[float, float]], str]:
    """{label: (% of a core, MiB)} over `window` seconds (processes of one label summed, the
    `browser` pids as one), and the load average at its end."""
    start = {}
    for pid in pids:
        try:
            start[pid] = cpu_seconds(pid)
        except OSError:
            pass
    t0 = time.monotonic()
    time.sleep(window)
    elapsed = time.monotonic() - t0
    with open("/proc/loadavg") as f:
        load = " ".join(f.read().split()[:3])
    figures: Dict[str, Tuple[float, float]] = {}
    for pid, used in start.items():
        try:
            cpu = 100.0 * (cpu_seconds(pid) - used) / elapsed
            mib = rss_anon_kib(pid) / 1024.0
        except OSError:
            continue
        name = BROWSER if pid in browser else label(pid)
        if name == "?":
            continue  # gone (a zombie)
        old = figures.get(name, (0.0, 0.0))
        figures[name] = (old[0] + cpu, old[1] + mib)
    return figures, load


def browser_pids() -> List[int]:
    """The headless chromium processes (the student's browser) running now."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open("/proc/%s/comm" % entry) as f:
                    if f.read().strip() in ("chromium", "chrome", "chromedriver"):
                        found.append(int(entry))
            except OSError:
                pass
    return found


def run_checkout(name: str, checkout: Path, window: float, settle: float) -> Dict[str, tuple]:
    results = {}
    with Lab(checkout) as lab:
        time.sleep(settle)
        results["idle"] = measure(lab.pids(), window) + (None,)
        lab.drive()
        time.sleep(settle)
        results["moving"] = measure(lab.pids(), window) + (None,)
        already = set(browser_pids())
        with chromium() as driver:
            driver.get("http://127.0.0.1:%d/?token=%s" % (lab.page_port, TOKEN))
            wait_for(lambda: driver.execute_script(
                "return Number(document.getElementById('turtle-canvas').dataset.frames || 0)") > 0, 60)
            time.sleep(settle)
            browser = [p for p in browser_pids() if p not in already]
            figures, load = measure(lab.pids() + browser, window, tuple(browser))
            chrome = figures.pop(BROWSER, (0.0, 0.0))
            results["page"] = (figures, load, chrome)
    for state in STATES:
        figures, load, chrome = results[state]
        print_state(name, state, figures, load, chrome)
    return results


def print_state(name: str, state: str, figures: Dict[str, Tuple[float, float]], load: str,
                chrome: Optional[Tuple[float, float]]) -> None:
    print("[%s] %s (load average %s)" % (name, state, load))
    for proc, (cpu, mib) in sorted(figures.items(), key=lambda kv: -kv[1][0]):
        print("    %-22s %6.2f %% of a core %7.1f MiB" % (proc, cpu, mib))
    total_cpu = sum(c for c, _ in figures.values())
    total_mib = sum(m for _, m in figures.values())
    print("    %-22s %6.2f %% of a core %7.1f MiB" % ("student's total", total_cpu, total_mib))
    if chrome is not None:
        print("    %-22s %6.2f %% of a core %7.1f MiB (the student's browser, not the hub's)" % ("chromium", *chrome))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--window", type=float, default=30.0, help="seconds each state is measured over")
    parser.add_argument("--settle", type=float, default=5.0, help="seconds each state settles first")
    parser.add_argument("--before", default="", help="a revision to measure first (built in a worktree under /tmp)")
    args = parser.parse_args()
    runs = []
    if args.before:
        runs.append(("before %s" % args.before, run_checkout("before", built_worktree(args.before), args.window,
                                                           args.settle)))
    runs.append(("after", run_checkout("after", ROOT, args.window, args.settle)))
    print("\nstudent's total (lab without JupyterLab), %% of a core / MiB; targets <= %.0f %% and <= %.0f MiB "
          "with JupyterLab" % (TARGET_CPU_PERCENT, TARGET_MIB))
    for state in STATES:
        cells = []
        for name, results in runs:
            figures, load, _ = results[state]
            cells.append("%s %.2f %% %.0f MiB (load %s)" % (name, sum(c for c, _ in figures.values()),
                                                           sum(m for _, m in figures.values()), load))
        print("  %-7s %s" % (state, " | ".join(cells)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
