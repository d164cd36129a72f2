"""Keep one run (a rostest, a grading job) from leaking processes, ports or disk.

Every process of a run carries an environment token (`COURSE_RUN_TOKEN=<uuid>`), inherited by
whatever it starts, even through setsid() or a double fork. After the run, every process whose
/proc/<pid>/environ holds the token is stopped and killed, whatever it did to its session,
process group or signal handlers. Files the run writes are capped (RLIMIT_FSIZE), so a node
printing without end is killed by SIGXFSZ instead of filling the disk. Where the machine allows
it (`unshare`: as root, or through a user namespace), the run also gets its own network
namespace with only a loopback device.
"""
from __future__ import annotations

import functools
import os
import random
import resource
import signal
import socket
import subprocess
import uuid
from typing import Dict, List, Optional, Sequence, Set

from course_net.ports import free_port  # noqa: F401 - the tests' free_port, re-exported
from course_sandbox import procs
from course_sandbox.policy import Limits
from course_sandbox.procs import descendants, signal_all

TOKEN_VAR = "COURSE_RUN_TOKEN"
# Largest file any process of a run may write: student logs, canvas pictures, JUnit XML (the
# sandbox's own per-file limit: one number).
MAX_FILE_BYTES = Limits().file_bytes


def new_token() -> str:
    return uuid.uuid4().hex


def token_env(env: Dict[str, str], token: str) -> Dict[str, str]:
    """`env` with the run's token set."""
    return dict(env, **{TOKEN_VAR: token})


def port_below_ephemeral_range(host: str = "127.0.0.1", ranges: str = "/proc/sys/net/ipv4/ip_local_port_range",
                               lowest: int = 20000) -> int:
    """A free TCP port below the kernel's ephemeral range, for a server that must be told its port
    before it binds (chromedriver): a port the kernel picked (free_port) can be handed to any
    process that binds port 0 in between, a ROS node of a test running beside, and a client then
    talks to that process instead. Below the range, only a process that names the port takes it."""
    try:
        with open(ranges) as f:
            first = int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        first = 32768
    candidates = list(range(lowest, max(lowest + 1, first)))
    random.shuffle(candidates)
    for port in candidates:
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
            try:
                sock.bind((host, port))
            except OSError:
                continue
            return port
    return free_port(host)


def sourced_env(setup: str, start: Optional[Dict[str, str]] = None, timeout: float = 120.0) -> Dict[str, str]:
    """The environment of a new bash after `source <setup>` (a catkin setup.bash), started from
    `start` (default: this process's). CalledProcessError when sourcing fails."""
    out = subprocess.run(["bash", "-c", 'source "$1" >/dev/null && exec env -0', "bash", str(setup)],
                         env=dict(os.environ if start is None else start), stdout=subprocess.PIPE,
                         stdin=subprocess.DEVNULL, check=True, timeout=timeout).stdout
    return dict(item.split("=", 1) for item in out.decode(errors="replace").split("\0") if "=" in item)


def pids_with_token(token: str) -> List[int]:
    """Every live process whose environment holds TOKEN_VAR=token (never this process)."""
    needle = ("%s=%s" % (TOKEN_VAR, token)).encode()
    found = []
    for pid in procs.pids():
        if pid == os.getpid():
            continue
        if needle in procs.environ(pid):  # [] when gone, or not ours
            found.append(pid)
    return found


def kill_run(token: str, root: Optional[int] = None, rounds: int = 20) -> Set[int]:
    """Kill every process of the run: the token holders and the tree below `root` (which catches
    a process that emptied its environment). Each round freezes them all (SIGSTOP, so a forking
    process cannot outrun us), then kills them. Returns the pids killed."""
    killed: Set[int] = set()
    for _ in range(rounds):
        pids = set(pids_with_token(token))
        if root is not None:
            pids.update(descendants(root))
        pids -= {os.getpid()}
        if not pids:
            break
        signal_all(pids, signal.SIGSTOP)
        signal_all(pids, signal.SIGKILL)
        killed |= pids
    return killed


def limit_file_size(pid: int, max_bytes: int = MAX_FILE_BYTES) -> None:
    """Cap the size of any file `pid` (and what it starts from now on) writes."""
    try:
        resource.prlimit(pid, resource.RLIMIT_FSIZE, (max_bytes, max_bytes))
    except (ProcessLookupError, PermissionError, ValueError):
        pass


@functools.lru_cache(maxsize=1)
def network_namespace_works() -> bool:
    """True when `unshare --net` can give a run its own loopback-only network here."""
    try:
        return subprocess.run(netns_prefix() + ["true"], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, timeout=20).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


def netns_prefix() -> List[str]:
    """A command prefix that runs the rest in a new network namespace with loopback up. As root:
    `unshare --net`. As an ordinary user: inside a user namespace that maps only the user
    (`--map-current-user`), whose capabilities bring loopback up and are then all dropped, so
    the run keeps the user's identity and rights."""
    if os.geteuid() == 0:
        return ["unshare", "--net", "--", "sh", "-c", 'ip link set lo up && exec "$@"', "netns"]
    return ["unshare", "--user", "--map-current-user", "--net", "--keep-caps", "--", "sh", "-c",
            'ip link set lo up && exec setpriv --inh-caps=-all --ambient-caps=-all -- "$@"', "netns"]


def isolated_command(command: Sequence[str], own_network: bool) -> List[str]:
    """`command`, in its own network namespace when asked for and possible."""
    if own_network and network_namespace_works():
        return netns_prefix() + list(command)
    return list(command)
