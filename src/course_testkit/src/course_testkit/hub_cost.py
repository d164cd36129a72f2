"""What one student's container costs, read from the kernel's counters (bench/hub_bench.py measures with it).

A container's cost is its cgroup's: CPU as the delta of the cgroup's own counter over a window
(cgroup v1 `cpuacct.usage`, ns, or v2 `cpu.stat` usage_usec), so a container's start-up is not
averaged in as `podman stats` does; memory as the cgroup's use less its file pages (v1:
`memory.usage_in_bytes` minus `total_active_file` and `total_inactive_file`; v2: `memory.current`
minus `file`): anonymous memory, tmpfs (the container's home and /tmp) and the kernel's, what the
cgroup cannot give back by dropping page cache; the kernel's part is also given apart (`kernel_bytes`).

Inside a container, each process is named by its command line (`process_group`) and its CPU
(`/proc/PID/stat` utime + stime) and anonymous memory (`/proc/PID/status` RssAnon) summed by
name. CPU of processes that ended during the window is the cgroup's delta less the processes'
sum ("ended in the window").

The hub's own processes (JupyterHub, configurable-http-proxy, podman's API service) are those
descended from the hub's start (`tree_cpu_s`).
"""
from __future__ import annotations

import os
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterable, List, Optional, Tuple

from course_sandbox import procs

CGROUP_ROOT = Path("/sys/fs/cgroup")
TICK_S = 1.0 / os.sysconf("SC_CLK_TCK")
MIB = 2 ** 20
ENDED = "ended in the window"
# name -> words of a command line (the first that matches names the process); order matters
GROUPS: Tuple[Tuple[str, Tuple[str, ...]], ...] = (
    ("student's own (rostopic pub)", ("rostopic pub", "pose_rate.py")),
    ("master", ("rosmaster",)),
    ("roscore's roslaunch", ("roscore", "roslaunch")),
    ("rosout", ("/rosout ", "rosout/rosout", "__name:=rosout")),
    ("turtlesim", ("turtlesim_node",)),
    ("lab view", ("lab_view", "roslab")),
    ("rosbridge", ("rosbridge",)),
    ("Xvnc", ("Xvnc", "Xtigervnc", "vncserver")),
    ("desktop session (WM, xterm)", ("jwm", "xterm", "desktop.xstartup", "websockify")),
    ("JupyterLab", ("jupyterhub-singleuser", "jupyter-lab", "jupyter_server", "jupyter-server", "ipykernel",
                    "jupyter", "course_workbench/workbench")),
    ("terminals (bash)", ("bash",)),
)
OTHER = "other"


def process_group(cmdline: str) -> str:
    """The name a process's cost is counted under."""
    for name, words in GROUPS:
        if any(word in cmdline for word in words):
            return name
    words = cmdline.split()
    return "%s (%s)" % (OTHER, " ".join(os.path.basename(w) for w in words[:2])[:40]) if words else OTHER


def container_pid(container: str, podman: List[str]) -> int:
    out = subprocess.run(podman + ["inspect", container, "-f", "{{.State.Pid}}"], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True, check=False).stdout.strip()
    if not out.isdigit() or int(out) == 0:
        raise RuntimeError("container %s has no process (podman inspect: %r)" % (container, out))
    return int(out)


class Cgroup:
    """A process's cgroup (v1 cpuacct and memory controllers, or v2's unified tree)."""

    def __init__(self, pid: int) -> None:
        self.v1: Dict[str, Path] = {}
        self.v2: Optional[Path] = None
        with open("/proc/%d/cgroup" % pid) as table:
            for line in table:
                _, controllers, path = line.rstrip("\n").split(":", 2)
                for controller in controllers.split(","):
                    if controller in ("cpuacct", "memory") and (CGROUP_ROOT / controller).is_dir():
                        self.v1[controller] = CGROUP_ROOT / controller / path.lstrip("/")
                if controllers == "" and not self.v1:
                    for top in (CGROUP_ROOT, CGROUP_ROOT / "unified"):
                        if (top / path.lstrip("/") / "cpu.stat").exists():
                            self.v2 = top / path.lstrip("/")
        if not ({"cpuacct", "memory"} <= set(self.v1) or self.v2):
            raise RuntimeError("no cpuacct and memory cgroup for process %d: %s" % (pid, self.v1))

    def cpu_s(self) -> float:
        """CPU seconds the cgroup has used since it was made (every process in it and below)."""
        if self.v2 is None:
            return int((self.v1["cpuacct"] / "cpuacct.usage").read_text()) / 1e9
        stat = _keyed((self.v2 / "cpu.stat").read_text())
        return stat["usage_usec"] / 1e6

    def memory_bytes(self) -> int:
        """In use less file pages (the module docstring)."""
        if self.v2 is None:
            stat = _keyed((self.v1["memory"] / "memory.stat").read_text())
            usage = int((self.v1["memory"] / "memory.usage_in_bytes").read_text())
            return usage - stat.get("total_active_file", 0) - stat.get("total_inactive_file", 0)
        stat = _keyed((self.v2 / "memory.stat").read_text())
        return int((self.v2 / "memory.current").read_text()) - stat.get("file", 0)

    def kernel_bytes(self) -> int:
        """The kernel's part of memory_bytes(): slab (mostly the dentries and inodes of files the
        container opened, charged to the first cgroup that read them, image layers included),
        page tables, kernel stacks, socket buffers. 0 where the kernel does not say."""
        if self.v2 is None:
            kmem = self.v1["memory"] / "memory.kmem.usage_in_bytes"
            return int(kmem.read_text()) if kmem.exists() else 0
        stat = _keyed((self.v2 / "memory.stat").read_text())
        if "kernel" in stat:
            return stat["kernel"]
        return sum(stat.get(k, 0) for k in ("slab", "kernel_stack", "pagetables", "sock", "percpu"))

    def pids(self) -> List[int]:
        top = self.v1["cpuacct"] if self.v2 is None else self.v2
        found: List[int] = []
        for folder, _, files in os.walk(top):
            if "cgroup.procs" in files:
                found.extend(int(p) for p in Path(folder, "cgroup.procs").read_text().split())
        return found


def _keyed(text: str) -> Dict[str, int]:
    return {k: int(v) for k, v in (line.split() for line in text.splitlines() if len(line.split()) == 2)}


def process_times(pids: Iterable[int]) -> Dict[int, Tuple[str, float, int]]:
    """pid -> (group name, CPU seconds used, RssAnon bytes); processes gone meanwhile are left out."""
    found = {}
    for pid in pids:
        try:
            cmdline = Path("/proc/%d/cmdline" % pid).read_bytes().replace(b"\0", b" ").decode(errors="replace")
            stat = Path("/proc/%d/stat" % pid).read_text()
            status = Path("/proc/%d/status" % pid).read_text()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        cpu = (int(fields[11]) + int(fields[12])) * TICK_S  # utime, stime (fields 14, 15 of stat)
        anon = next((int(line.split()[1]) * 1024 for line in status.splitlines() if line.startswith("RssAnon:")), 0)
        if not cmdline.strip():  # a kernel thread or a zombie
            continue
        found[pid] = (process_group(cmdline), cpu, anon)
    return found


def tree_cpu_s(root: int) -> float:
    """CPU seconds of the living processes descended from `root`, itself included (the hub's
    start: JupyterHub, configurable-http-proxy, podman's API service; not the containers, whose
    conmon leaves the tree)."""
    uses = (procs.usage(pid) for pid in [root] + procs.descendants(root))
    return sum(use.cpu_seconds for use in uses if use is not None)


@dataclass
class Window:
    """One container's cost over a window: CPU % of a core and memory, in total and by process."""
    seconds: float
    cpu_pct: float
    memory_mib: float
    kernel_mib: float
    by_group: Dict[str, Tuple[float, float]] = field(default_factory=dict)  # name -> (CPU %, RssAnon MiB)
    hub_cpu_pct: float = float("nan")
    load: str = ""


def loadavg() -> str:
    return " ".join(Path("/proc/loadavg").read_text().split()[:3])


class Meter:
    """Windows of one container's counters (and, if given, the hub's session)."""

    def __init__(self, container: str, podman: List[str], hub_pid: Optional[int] = None) -> None:
        self.container = container
        self.cgroup = Cgroup(container_pid(container, podman))
        self.hub_pid = hub_pid

    def snapshot(self) -> Snapshot:
        return Snapshot(process_times(self.cgroup.pids()), self.cgroup.cpu_s(), self._hub(), time.monotonic())

    def since(self, first: Snapshot) -> Window:
        """The cost from `first` until now."""
        last = self.snapshot()
        elapsed = last.at - first.at
        groups: Dict[str, List[float]] = {}
        for pid, (name, cpu, anon) in last.processes.items():
            start = first.processes[pid][1] if pid in first.processes else 0.0  # started in the window: all of it
            entry = groups.setdefault(name, [0.0, 0.0])
            entry[0] += cpu - start
            entry[1] += anon
        total = last.cpu_s - first.cpu_s
        counted = sum(cpu for cpu, _ in groups.values())
        if total - counted > 0.005 * elapsed:
            groups[ENDED] = [total - counted, 0.0]
        return Window(elapsed, 100.0 * total / elapsed, self.cgroup.memory_bytes() / MIB,
                      self.cgroup.kernel_bytes() / MIB,
                      {name: (100.0 * cpu / elapsed, anon / MIB) for name, (cpu, anon) in groups.items()},
                      100.0 * (last.hub_s - first.hub_s) / elapsed if self.hub_pid else float("nan"), loadavg())

    def _hub(self) -> float:
        return tree_cpu_s(self.hub_pid) if self.hub_pid else 0.0


@dataclass
class Snapshot:
    processes: Dict[int, Tuple[str, float, int]]
    cpu_s: float
    hub_s: float
    at: float


def windows(meters: List[Meter], seconds: float) -> List[Window]:
    """Every meter's window over the same `seconds`, side by side."""
    first = [m.snapshot() for m in meters]
    time.sleep(seconds)
    return [m.since(f) for m, f in zip(meters, first)]


def cpu_rate(meters: List[Meter], seconds: float) -> float:
    """% of a core the meters' containers used together over the next `seconds`."""
    before, began = sum(m.cgroup.cpu_s() for m in meters), time.monotonic()
    time.sleep(seconds)
    return 100.0 * (sum(m.cgroup.cpu_s() for m in meters) - before) / (time.monotonic() - began)


def settle(meters: List[Meter], step_s: float = 2.0, least_s: float = 10.0, most_s: float = 90.0,
           tolerance_pct: float = 1.0) -> float:
    """Wait until two successive `step_s` windows' CPU rates (the meters' containers together)
    differ by at most `tolerance_pct` points of a core or 15 % of the rate, after at least
    `least_s` and at most `most_s`; the seconds waited. This is the measurement's choice of
    "settled" (start-ups and page loads done), not a synchronisation."""
    began = time.monotonic()
    last = cpu_rate(meters, step_s)
    while time.monotonic() - began < most_s:
        now = cpu_rate(meters, step_s)
        if abs(now - last) <= max(tolerance_pct, 0.15 * max(now, last)) and time.monotonic() - began >= least_s:
            break
        last = now
    return time.monotonic() - began
