"""A terminal that hands over each key as it is typed: raw (non-canonical, no echo) input.

Turning the bytes read into key names is course_keyboard.decoder's job.
"""
from __future__ import annotations

import os
import select
import sys
import termios
from typing import Optional


class NotATerminal(RuntimeError):
    """stdin is not a TTY, so single key presses cannot be read."""


class RawTerminal:
    """Context manager: the terminal on `fd` delivers each key at once, unechoed; restored on exit.

    Signals (Ctrl+C) stay enabled, as with upstream turtle_teleop_key. Every keyboard node
    of the workspace (turtle_teleop_key, mybot_teleop, lab2's turtle_controller.py) reads through it.
    """

    def __init__(self, fd: Optional[int] = None, program: str = "this node") -> None:
        self.fd = sys.stdin.fileno() if fd is None else fd
        if not os.isatty(self.fd):
            raise NotATerminal("%s reads single key presses, but its stdin is not a terminal: run it "
                               "with rosrun in a terminal (or give it one with launch-prefix=\"xterm -e\" "
                               "in a launch file)" % program)
        self._saved = None

    def __enter__(self) -> "RawTerminal":
        self._saved = termios.tcgetattr(self.fd)
        raw = termios.tcgetattr(self.fd)
        raw[3] &= ~(termios.ICANON | termios.ECHO)
        raw[6][termios.VMIN] = 1
        raw[6][termios.VTIME] = 0
        termios.tcsetattr(self.fd, termios.TCSANOW, raw)
        return self

    def read(self, timeout: float) -> bytes:
        """The bytes typed so far, waiting at most `timeout` seconds; b'' if none.

        Raises EOFError when the terminal is closed.
        """
        ready, _, _ = select.select([self.fd], [], [], timeout)
        if not ready:
            return b""
        data = os.read(self.fd, 64)
        if not data:
            raise EOFError("the terminal was closed")
        return data

    def __exit__(self, *_exc) -> None:
        if self._saved is not None:
            try:
                termios.tcsetattr(self.fd, termios.TCSADRAIN, self._saved)
            except termios.error:
                pass  # the terminal is already gone
            self._saved = None
