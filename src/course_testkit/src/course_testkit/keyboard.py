"""Type on a node's keyboard: the node's stdin is the slave side of a pseudo-terminal
and the test writes key presses (arrow escape sequences) to the master side."""
from __future__ import annotations

import os
import pty
from typing import Optional, Sequence

from course_testkit.nodes import NodeProcess, find_executable

ARROWS = {"up": b"\x1b[A", "down": b"\x1b[B", "right": b"\x1b[C", "left": b"\x1b[D"}


class PtyKeyboard:
    """Runs a command with a pseudo-terminal as stdin; press() types into it."""

    def __init__(self, command: Sequence[str], log_path: Optional[str] = None) -> None:
        self.master, slave = pty.openpty()
        try:
            self.node = NodeProcess(command, stdin=slave, log_path=log_path)
        finally:
            os.close(slave)

    @classmethod
    def rosrun(cls, pkg: str, node_type: str, args: Sequence[str] = (), **kwargs) -> "PtyKeyboard":
        return cls([find_executable(pkg, node_type)] + list(args), **kwargs)

    def press(self, key: str) -> None:
        """Type an arrow ('up', 'down', 'left', 'right') or any literal characters."""
        os.write(self.master, ARROWS.get(key, key.encode()))

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
