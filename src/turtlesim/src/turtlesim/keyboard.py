"""Keys from a terminal: raw (non-canonical, no echo) input and arrow-key decoding."""
from __future__ import annotations

import os
import select
import sys
import termios
from typing import List, Optional

ARROWS = {ord("A"): "up", ord("B"): "down", ord("C"): "right", ord("D"): "left"}
ESC = 0x1B


class NotATerminal(RuntimeError):
    """stdin is not a TTY, so single key presses cannot be read."""


class KeyDecoder:
    """Turns bytes read from a terminal into key names: 'up', 'down', 'left', 'right' or the character.

    Arrow keys arrive as ESC [ A..D (or ESC O A..D in application mode), possibly
    split across reads; an unfinished sequence waits for the next `feed`.
    """

    def __init__(self) -> None:
        self._pending = b""

    def feed(self, data: bytes) -> List[str]:
        buf = self._pending + data
        keys: List[str] = []
        i = 0
        while i < len(buf):
            byte = buf[i]
            if byte != ESC:
                keys.append(chr(byte))
                i += 1
                continue
            if i + 1 >= len(buf) or (buf[i + 1] in b"[O" and i + 2 >= len(buf)):
                break  # incomplete escape sequence: wait for more bytes
            if buf[i + 1] in b"[O" and buf[i + 2] in ARROWS:
                keys.append(ARROWS[buf[i + 2]])
                i += 3
            else:
                i += 2 if buf[i + 1] in b"[O" else 1  # unknown sequence: skip its introducer
        self._pending = buf[i:]
        return keys


class RawTerminal:
    """Context manager: the terminal on `fd` delivers each key at once, unechoed; restored on exit.

    Signals (Ctrl+C) stay enabled, as with upstream turtle_teleop_key. Every keyboard node
    of the workspace (turtle_teleop_key, mybot_teleop, turtle_controller.py) reads through it.
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
