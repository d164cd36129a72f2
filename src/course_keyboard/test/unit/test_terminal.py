"""RawTerminal on a pseudo-terminal: raw mode while inside, echo restored after; a pipe is refused."""
import os
import pty
import termios

import pytest

from course_keyboard.terminal import NotATerminal, RawTerminal


def test_raw_terminal_refuses_a_pipe_naming_the_program():
    r, w = os.pipe()
    try:
        with pytest.raises(NotATerminal, match="teleop reads single key presses, but its stdin is not a terminal"):
            RawTerminal(r, program="teleop")
    finally:
        os.close(r)
        os.close(w)


def test_raw_mode_reads_keys_and_restores_echo():
    master, slave = pty.openpty()
    try:
        assert termios.tcgetattr(slave)[3] & termios.ECHO
        with RawTerminal(fd=slave) as term:
            assert not termios.tcgetattr(slave)[3] & termios.ECHO
            os.write(master, b"\x1b[A")
            assert term.read(2.0) == b"\x1b[A"
            assert term.read(0.01) == b""
        assert termios.tcgetattr(slave)[3] & termios.ECHO
    finally:
        os.close(master)
        os.close(slave)
