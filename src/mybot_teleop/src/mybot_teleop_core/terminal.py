"""Read single key presses from a real terminal, and always give the terminal back.

The terminal goes into "cbreak" mode (no line buffering, no echo; Ctrl+C still
raises SIGINT) and its previous settings are restored on exit, even on errors.
"""
from __future__ import annotations

import os
import select
import sys
import termios
from typing import Optional


class NotATerminal(RuntimeError):
    """stdin is a pipe, a file or /dev/null: key presses cannot be read from it."""


NOT_A_TTY_MESSAGE = (
    "%s reads the keyboard, but its standard input is not a terminal. "
    "Run it in a terminal (rosrun, or roslaunch from a terminal), not with stdin "
    "redirected or from a launch file started in the background.")


class RawTerminal:
    """Context manager: `with RawTerminal() as term: term.read(0.1)` returns bytes or b''."""

    def __init__(self, fd: Optional[int] = None, program: str = "this node") -> None:
        self.fd = sys.stdin.fileno() if fd is None else fd
        self.program = program
        self._saved = None

    def __enter__(self) -> "RawTerminal":
        if not os.isatty(self.fd):
            raise NotATerminal(NOT_A_TTY_MESSAGE % self.program)
        self._saved = termios.tcgetattr(self.fd)
        mode = termios.tcgetattr(self.fd)
        mode[3] &= ~(termios.ICANON | termios.ECHO)  # lflags: no line editing, no echo
        mode[6][termios.VMIN] = 1
        mode[6][termios.VTIME] = 0
        termios.tcsetattr(self.fd, termios.TCSANOW, mode)
        return self

    def read(self, timeout: float) -> bytes:
        """The bytes typed so far, waiting at most `timeout` seconds; b'' if none."""
        ready, _, _ = select.select([self.fd], [], [], timeout)
        if not ready:
            return b""
        data = os.read(self.fd, 64)
        if not data:
            raise EOFError("the terminal was closed")
        return data

    def restore(self) -> None:
        if self._saved is not None:
            try:
                termios.tcsetattr(self.fd, termios.TCSADRAIN, self._saved)
            except termios.error:
                pass  # the terminal is already gone
            self._saved = None

    def __exit__(self, *exc) -> None:
        self.restore()
