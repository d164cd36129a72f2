"""Start a node the way `rosrun PKG TYPE ARGS...` would, as a child process we own."""
from __future__ import annotations

import os
import signal
import subprocess
from typing import IO, TYPE_CHECKING, List, Optional, Sequence, Union

import roslib.packages

if TYPE_CHECKING:
    from course_sandbox.run import RunSandbox


def find_executable(pkg: str, node_type: str) -> str:
    """The path rosrun would run for PKG TYPE; a clear error when there is none."""
    paths = roslib.packages.find_node(pkg, node_type)
    if not paths:
        raise FileNotFoundError("no executable [%s] in package [%s] (is it built and chmod +x?)"
                                % (node_type, pkg))
    return paths[0]


# coreutils' stdbuf library: preloaded, it sets a C program's stdout buffering from _STDBUF_O.
STDBUF_LIBRARY = "/usr/libexec/coreutils/libstdbuf.so"


def unbuffered_env(env: Optional[dict] = None) -> dict:
    """`env` (default: ours) with output flushed as it is written, as on the terminal a student
    runs their node in: Python's unbuffered, a C or C++ program's stdout line-buffered (a node's
    plain print(), printf("...\\n") or std::cout << "...\\n" reaches the log as it happens, not
    when the node exits or its buffer fills)."""
    out = dict(os.environ if env is None else env, PYTHONUNBUFFERED="1")
    if os.path.exists(STDBUF_LIBRARY) and STDBUF_LIBRARY not in out.get("LD_PRELOAD", "").split():
        out["LD_PRELOAD"] = " ".join(p for p in (out.get("LD_PRELOAD", ""), STDBUF_LIBRARY) if p)
        out["_STDBUF_O"] = "L"
    return out


class NodeProcess:
    """A child node with its own process group, so stop() (Ctrl+C) and end() (SIGKILL) also end
    anything it started in that group.
    Its output is flushed line by line (unbuffered_env)."""

    def __init__(self, command: Sequence[str], stdin: Union[int, IO, None] = None,
                 log_path: Optional[str] = None, env: Optional[dict] = None,
                 stdout: Union[int, IO, None] = None, sandbox: Optional["RunSandbox"] = None) -> None:
        """Output goes to `stdout` if given, else to `log_path` (or nowhere). With `sandbox` (a
        course_sandbox.run.RunSandbox), the command runs inside it as untrusted student code:
        its output still goes to the file this (trusted) process opened."""
        self.command: List[str] = list(command)
        self.log_path: Optional[str] = log_path if stdout is None else None
        self._log = open(log_path, "wb") if log_path else subprocess.DEVNULL
        argv, env, cwd = self.command, unbuffered_env(env), None
        if sandbox is not None:
            argv, env, cwd = sandbox.prepare(self.command, env)
        self.proc = subprocess.Popen(argv, stdin=stdin, stdout=self._log if stdout is None else stdout,
                                     stderr=subprocess.STDOUT, env=env, cwd=cwd, start_new_session=True)

    @classmethod
    def rosrun(cls, pkg: str, node_type: str, args: Sequence[str] = (), **kwargs) -> "NodeProcess":
        return cls([find_executable(pkg, node_type)] + list(args), **kwargs)

    def output(self) -> str:
        """What the node has printed so far (empty when its output is not logged to a file)."""
        if not self.log_path:
            return ""
        with open(self.log_path, errors="replace") as f:
            return f.read()

    def running(self) -> bool:
        return self.proc.poll() is None

    def wait(self, timeout: float = 10.0) -> Optional[int]:
        """The node's exit code once it exits by itself, or None if it is still running after `timeout`."""
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            return None

    def end(self) -> Optional[int]:
        """SIGKILL to the group at once, for a check's clean-up once its verdict is in: how the
        node would take Ctrl+C no longer matters, and a rospy node's own shutdown costs about half
        a CPU second and as much wall time (docs/benchmarks.md). Its exit code."""
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait(5)
            except (ProcessLookupError, subprocess.TimeoutExpired):
                pass
        return self.stop()  # reaps it (or, stuck, tries again) and closes the log

    def stop(self, timeout: float = 10.0) -> Optional[int]:
        """SIGINT (like Ctrl+C), then SIGKILL if the group does not go away."""
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGINT)
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait(5)
            except ProcessLookupError:
                pass
        if self._log is not subprocess.DEVNULL:
            self._log.close()
        return self.proc.returncode
