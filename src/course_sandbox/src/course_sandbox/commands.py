"""The command lines that put a process in a sandbox (pure functions: a policy in, an argv out).

One sandbox per milestone run is a *keeper*: bubblewrap makes the namespaces and the filesystem
view and runs a small reaper as their first process (KEEPER_INIT); every student process of the
run joins them with nsenter. Killing the keeper's namespace init ends every process in the namespace,
whatever it did (new sessions, a cleared environment, double forks). A build is one bubblewrap
call around catkin_make.

Signals: a check stops a student node with Ctrl+C (SIGINT to its process group). bubblewrap and
nsenter die of SIGINT, which would tear the sandbox down before the node has handled its
Ctrl+C; so they run with SIGINT and SIGTERM ignored (`env --ignore-signal`), and the student's
command gets them back (`env --default-signal`). nsenter waits for the node and gives back its
exit status.

Working directory: a student's process changes to it inside the sandbox, by its path in the
sandbox's view (`env --chdir`; bubblewrap's `--chdir` for a build). nsenter's `--wd` would open
the folder before entering the mount namespace: the process would then sit in the host's mount of
it, which the sandbox's root cannot name, so getcwd() falls back to reading each folder above it,
and one the sandbox user cannot list (the grader's 0711 work folder) makes every shell start
with `sh: 0: getcwd() failed: Permission denied` in the student's log (and Python `-c` fail to
import).

/dev is a small tmpfs with null, zero, full, random, urandom and tty, not bubblewrap's `--dev`:
mounting a devpts makes bubblewrap nest a second user namespace, which nsenter could not join.
A node's terminal (a pseudo-terminal the check opened) reaches it as an inherited descriptor.
"""
from __future__ import annotations

import os
from typing import Callable, List, Sequence, Tuple

from course_sandbox import levels
from course_sandbox.policy import Limits, Policy

DEVICES = ("null", "zero", "full", "random", "urandom", "tty")
SHM_BYTES = 64 * 1024 * 1024
IGNORE_STOP_SIGNALS = ["env", "--ignore-signal=INT,TERM"]
# The first process of a run's PID namespace (bubblewrap's --as-pid-1): it reaps the orphans the
# student's processes leave and ignores every signal a student could send it, so the namespace
# lives until the trusted side kills it (a PID namespace's init gets no signal it does not handle
# from inside, SIGKILL included).
KEEPER_PYTHON = "/usr/bin/python3"
KEEPER_NAME = "python3"  # its /proc/<pid>/comm once bubblewrap has exec'd it
KEEPER_INIT = ("import os, signal, time\n"
               "for s in set(signal.Signals) - {signal.SIGKILL, signal.SIGSTOP, signal.SIGCHLD}:\n"
               "    signal.signal(s, signal.SIG_IGN)\n"
               "while True:\n"
               "    try:\n"
               "        os.wait()\n"
               "    except ChildProcessError:\n"
               "        time.sleep(0.2)\n")
RESTORE_STOP_SIGNALS = ["env", "--default-signal=INT,TERM"]


def user_prefix(policy: Policy) -> List[str]:
    """Become the sandbox user (only when the level switches users, i.e. the grader is root)."""
    if not levels.switches_user(policy.level):
        return []
    group = str(policy.gid) if policy.gid >= 0 else policy.user
    prefix = ["setpriv", "--reuid", policy.user, "--regid", group, "--clear-groups"]
    if not levels.uses_namespaces(policy.level):
        prefix.append("--no-new-privs")  # bubblewrap sets it itself
    return prefix + ["--"]


def limits_prefix(limits: Limits, level: str, counted: bool = False) -> List[str]:
    """prlimit for one process. RLIMIT_NPROC counts per user *namespace* (Linux >= 5.14), so inside
    the sandbox it bounds this sandbox alone; without namespaces it would count the grader's own
    processes too, so it is set only where the user is the sandbox user. `counted`: a pids
    cgroup of the run's own is the process limit (course_sandbox.pids_cgroup), and no RLIMIT_NPROC
    is set (without namespaces it would be the sandbox user's, shared by every run at once)."""
    args = ["prlimit", "--as=%d" % limits.address_space_bytes,
            "--cpu=%d:%d" % (limits.cpu_seconds, limits.cpu_seconds + 5),
            "--fsize=%d" % limits.file_bytes, "--core=0"]
    if level != levels.NONE and not counted:
        args.append("--nproc=%d" % limits.processes)
    return args + ["--"]


def _depth(path: str) -> int:
    return len([part for part in path.split(os.sep) if part])


def _ancestors(path: str) -> List[str]:
    """'/a/b/c' -> ['/a', '/a/b'] (not / and not the path itself)."""
    parts = [p for p in path.split(os.sep) if p]
    return ["/" + "/".join(parts[:i]) for i in range(1, len(parts))]


def view_args(policy: Policy, can_traverse: Callable[[str], bool]) -> List[str]:
    """bubblewrap's filesystem view: the system read-only, a private /tmp and /dev/shm, the
    hidden paths empty, the readable ones read-only and the writable ones writable.

    Mounts go from the shallowest path to the deepest, so a deeper rule wins over the folder it
    is in (the student's workspace inside the hidden output folder). bubblewrap runs as the
    sandbox user: a hidden path that user cannot reach (below a 0700 home) is unreadable already
    and left as it is (bubblewrap could not mount over it); the bound folders must be reachable
    (the grader checks that before it starts: course_grader.sandboxing)."""
    args = ["--ro-bind", "/", "/", "--proc", "/proc", "--tmpfs", "/dev"]
    for dev in DEVICES:
        if os.path.exists("/dev/" + dev):
            args += ["--dev-bind", "/dev/" + dev, "/dev/" + dev]
    args += ["--symlink", "/proc/self/fd", "/dev/fd", "--symlink", "/proc/self/fd/0", "/dev/stdin",
             "--symlink", "/proc/self/fd/1", "/dev/stdout", "--symlink", "/proc/self/fd/2", "/dev/stderr",
             "--size", str(SHM_BYTES), "--tmpfs", "/dev/shm",
             "--size", str(policy.limits.tmp_bytes), "--tmpfs", "/tmp"]
    binds = [(path, 1, ["--ro-bind", path, path]) for path in policy.readable if os.path.isdir(path)]
    binds += [(path, 2, ["--bind", path, path]) for path in policy.writable if os.path.isdir(path)]
    made = ["/tmp"] + [path for path, _, _ in binds]  # below these, bubblewrap makes what it needs

    def reachable(path: str) -> bool:
        return all(can_traverse(folder) or any(folder == m or folder.startswith(m + os.sep) for m in made)
                   for folder in _ancestors(path))
    rules: List[Tuple[str, int, List[str]]] = list(binds)
    for path in policy.hidden:
        if os.path.exists(path) and reachable(path):
            rules.append((path, 0, ["--tmpfs", path] if os.path.isdir(path) else ["--ro-bind", "/dev/null", path]))
    for _, _, rule in sorted(rules, key=lambda r: (_depth(r[0]), r[1])):
        args += rule
    return args


def namespace_args() -> List[str]:
    return ["--unshare-user", "--unshare-pid", "--unshare-ipc", "--unshare-uts", "--unshare-cgroup-try",
            "--die-with-parent"]


def keeper_command(policy: Policy, can_traverse: Callable[[str], bool]) -> List[str]:
    """The process that holds one run's namespaces (levels with namespaces only)."""
    return (user_prefix(policy) + IGNORE_STOP_SIGNALS + ["bwrap"] + namespace_args()
            + view_args(policy, can_traverse)
            + ["--as-pid-1", "--", KEEPER_PYTHON, "-I", "-S", "-c", KEEPER_INIT])


def enter_command(policy: Policy, init_pid: int, command: Sequence[str], cwd: str,
                  counted: bool = False) -> List[str]:
    """`command` as a process of the run's sandbox, whose namespace init is `init_pid`, in the folder
    `cwd` as the sandbox shows it (see the module docstring). Without namespaces: as the sandbox
    user (if any) with the limits. `counted`: see limits_prefix."""
    inner = (RESTORE_STOP_SIGNALS + ["--chdir=" + cwd] + limits_prefix(policy.limits, policy.level, counted)
             + list(command))
    if not levels.uses_namespaces(policy.level):
        return user_prefix(policy) + inner
    return (user_prefix(policy) + IGNORE_STOP_SIGNALS
            + ["nsenter", "--target", str(init_pid), "--user", "--mount", "--pid", "--preserve-credentials", "--"]
            + inner)


def oneshot_command(policy: Policy, command: Sequence[str], cwd: str,
                    can_traverse: Callable[[str], bool], counted: bool = False) -> List[str]:
    """`command` in a sandbox of its own (a build): it ends when the command ends. `counted`: see
    limits_prefix."""
    inner = limits_prefix(policy.limits, policy.level, counted) + list(command)
    if not levels.uses_namespaces(policy.level):
        return user_prefix(policy) + inner
    return (user_prefix(policy) + ["bwrap"] + namespace_args() + view_args(policy, can_traverse)
            + ["--chdir", cwd, "--"] + inner)
