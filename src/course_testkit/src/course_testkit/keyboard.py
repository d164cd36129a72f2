"""Type on a node's keyboard: the node's stdin is the slave side of a pseudo-terminal
and the test writes key presses (arrow escape sequences) to the master side."""
from __future__ import annotations

import os
import pty
import select
import subprocess
import time
from typing import Callable, Optional, Sequence, TypeVar

from course_testkit.nodes import NodeProcess, find_executable
from course_testkit.waiting import wait_for

T = TypeVar("T")

ARROWS = {"up": b"\x1b[A", "down": b"\x1b[B", "right": b"\x1b[C", "left": b"\x1b[D"}


class PtyKeyboard:
    """Runs a command with a pseudo-terminal as stdin; press() types into it."""

    def __init__(self, command: Sequence[str], log_path: Optional[str] = None, env: Optional[dict] = None,
                 output_on_pty: bool = False) -> None:
        """`output_on_pty`: the node also writes to the terminal, and read_until() reads what it printed."""
        self.master, slave = pty.openpty()
        self.output = b""
        try:
            self.node = NodeProcess(command, stdin=slave, log_path=log_path, env=env,
                                    stdout=slave if output_on_pty else None)
        finally:
            os.close(slave)

    def read_until(self, text: bytes, timeout: float = 10.0) -> bool:
        """Collect what the node printed on the terminal until `text` shows up (True) or `timeout` passes."""
        deadline = time.monotonic() + timeout
        while text not in self.output and time.monotonic() < deadline:
            ready, _, _ = select.select([self.master], [], [], 0.05)
            if not ready:
                continue
            try:
                chunk = os.read(self.master, 4096)
            except OSError:  # the node closed the terminal
                break
            if not chunk:
                break
            self.output += chunk
        return text in self.output

    def wait(self, timeout: float = 10.0) -> Optional[int]:
        """The node's exit code once it exits by itself, or None if it is still running after `timeout`."""
        try:
            return self.node.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            return None

    @classmethod
    def rosrun(cls, pkg: str, node_type: str, args: Sequence[str] = (), **kwargs) -> "PtyKeyboard":
        return cls([find_executable(pkg, node_type)] + list(args), **kwargs)

    def press(self, key: str) -> None:
        """Type an arrow ('up', 'down', 'left', 'right') or any literal characters."""
        os.write(self.master, ARROWS.get(key, key.encode()))

    def press_until(self, key: str, condition: Callable[[], T], tries: int = 20, interval: float = 1.0) -> T:
        """Press `key`, again every `interval` seconds (at most `tries` times), until condition() is
        truthy; return its last value. A node still starting, or whose subscribers are not all
        connected yet, can miss a press; stops early if the node exits."""
        value = condition()
        for _ in range(tries):
            if value or not self.node.running():
                break
            self.press(key)
            value = wait_for(condition, interval)
        return value

    def terminal_settings_echo(self) -> bool:
        """Whether the terminal echoes input (the node should turn echo off while running)."""
        import termios
        return bool(termios.tcgetattr(self.master)[3] & termios.ECHO)

    def stop(self, timeout: float = 10.0) -> Optional[int]:
        code = self.node.stop(timeout)
        try:
            os.close(self.master)
        except OSError:
            pass
        return code
