"""`make demo` listens on loopback only: every TCP socket its processes listen on, as `ss` sees it.

The README promises a loopback-only demo: a ROS 1 master has no authentication, so anyone who
reaches one of its ports can drive the turtles or kill the nodes. The demo runs (with a short
scene) while `ss -ltnp` is sampled until it exits; every listening socket owned by one of its
processes (its run token or its process tree) must be bound to 127.0.0.1 or ::1, and the master,
turtlesim and the demo's own node must each have been seen listening. Nothing may be left running.
"""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path
from typing import Dict, Iterable, Tuple

from course_checks.isolation import descendants, kill_run, new_token, pids_with_token, token_env
from course_checks.nodes import unbuffered_env
from course_checks.waiting import wait_for

ROOT = Path(__file__).resolve().parents[1]
DEMO = ROOT / "tools" / "demo.py"
LOOPBACK = ("127.0.0.1", "::1")
# The demo's processes, by a word of their command line.
ROLES = ("rosmaster", "turtlesim_node", "demo.py")
SCENE_SECONDS = "1"
TIMEOUT_S = 120.0  # start-up on a loaded machine; a quiet one needs about 5 s
SAMPLE_INTERVAL_S = 0.05

Listener = Tuple[str, int]  # (local address as ss prints it, pid)


def command_line(pid: int) -> str:
    try:
        with open("/proc/%d/cmdline" % pid, "rb") as f:
            return f.read().replace(b"\0", b" ").decode(errors="replace").strip()
    except OSError:
        return "?"


def listeners(pids: Iterable[int]) -> Dict[Listener, str]:
    """The listening TCP sockets of `pids` right now, with their owner's command line."""
    wanted = set(pids)
    table = subprocess.run(["ss", "-ltnpH"], capture_output=True, text=True, check=True).stdout
    found: Dict[Listener, str] = {}
    for line in table.splitlines():
        fields = line.split()
        if len(fields) < 6:
            continue
        for pid in {int(p) for p in re.findall(r"pid=(\d+)", line)} & wanted:
            found[(fields[3], pid)] = command_line(pid)
    return found


def host(local_address: str) -> str:
    """The bound address of `127.0.0.1:80`, `[::1]:80`, `*:80` or `127.0.0.1%lo:80`."""
    return local_address.rsplit(":", 1)[0].strip("[]").split("%")[0]


def test_every_listening_socket_of_the_demo_is_on_loopback(tmp_path: Path) -> None:
    token = new_token()
    output = tmp_path / "demo.out"
    with open(output, "wb") as out:
        demo = subprocess.Popen([sys.executable, str(DEMO), "--seconds", SCENE_SECONDS, "--out", str(tmp_path)],
                                stdout=out, stderr=subprocess.STDOUT, env=token_env(unbuffered_env(), token),
                                start_new_session=True)
    seen: Dict[Listener, str] = {}

    def demo_ended() -> bool:
        ended = demo.poll() is not None
        if not ended:
            now = listeners(set(pids_with_token(token)) | set(descendants(demo.pid)) | {demo.pid})
            for key, cmd in now.items():
                # A process that is exiting may still own its socket but has no command line
                # left: keep the one an earlier sample read.
                if cmd or key not in seen:
                    seen[key] = cmd
        return ended

    try:
        ended = wait_for(demo_ended, timeout=TIMEOUT_S, interval=SAMPLE_INTERVAL_S)
        wait_for(lambda: not pids_with_token(token), timeout=10)
        left = sorted(command_line(pid) for pid in pids_with_token(token))
    finally:
        kill_run(token, root=None if demo.poll() is not None else demo.pid)
        if demo.poll() is None:
            demo.kill()
        demo.wait(10)
    said = output.read_text(errors="replace")
    assert ended, "the demo did not finish within %.0f s; it said:\n%s" % (TIMEOUT_S, said)
    assert demo.returncode == 0 and "canvas saved to" in said, "the demo failed (exit %s):\n%s" % (
        demo.returncode, said)
    assert not left, "the demo left processes running: %s" % left

    table = "\n".join("  %s  pid %d  %s" % (address, pid, cmd) for (address, pid), cmd in sorted(seen.items()))
    assert seen, "ss showed no listening socket of the demo's processes"
    exposed = [address for address, _pid in seen if host(address) not in LOOPBACK]
    assert not exposed, "the demo listens beyond loopback on %s:\n%s" % (", ".join(exposed), table)
    missing = [role for role in ROLES if not any(role in cmd for cmd in seen.values())]
    assert not missing, "never saw %s listening; seen:\n%s" % (", ".join(missing), table)
    master = re.search(r"master at http://localhost:(\d+)", said)
    assert master and any(address.endswith(":" + master.group(1)) for address, _pid in seen), (
        "the master's port is not among the sockets seen:\n%s\n%s" % (said, table))
