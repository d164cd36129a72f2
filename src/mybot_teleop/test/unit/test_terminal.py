import os
import pty
import termios

import pytest

from mybot_teleop_core.terminal import NotATerminal, RawTerminal


def test_pipe_is_refused_with_a_clear_message():
    r, w = os.pipe()
    try:
        with pytest.raises(NotATerminal, match="not a terminal"):
            with RawTerminal(fd=r, program="teleop"):
                pass
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
