"""Key decoding for turtle_teleop_key, the draw_square driver and the ticker schedule."""
import math
import os
import pty
import termios
import threading
import time

import pytest

from turtlesim.keyboard import KeyDecoder, NotATerminal, RawTerminal
from turtlesim.square import SquareDriver
from turtlesim.ticker import Ticker
from turtlesim.turtle import Turtle


def test_arrow_sequences_decode():
    assert KeyDecoder().feed(b"\x1b[A\x1b[B\x1b[C\x1b[Dq") == ["up", "down", "right", "left", "q"]


def test_application_mode_arrows():
    assert KeyDecoder().feed(b"\x1bOA") == ["up"]


def test_sequence_split_across_reads():
    d = KeyDecoder()
    assert d.feed(b"\x1b") == []
    assert d.feed(b"[") == []
    assert d.feed(b"Ds") == ["left", "s"]


def test_unknown_escape_sequences_are_skipped():
    assert KeyDecoder().feed(b"\x1b[Zq") == ["Z", "q"]


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


def test_square_driver_closes_a_square():
    turtle = Turtle(5.0, 5.0, 0.0)
    driver = SquareDriver(side=2.0)
    visited = []
    for step in range(5000):
        linear, angular = driver.command(turtle.x, turtle.y, turtle.theta)
        turtle.command(linear, 0.0, angular, now=0.0)
        turtle.step(0.016, now=0.0)
        if driver.corners > len(visited):
            visited.append((turtle.x, turtle.y))
        if driver.corners == 4:
            break
    expected = [(7.0, 5.0), (7.0, 7.0), (5.0, 7.0), (5.0, 5.0)]
    for (x, y), (ex, ey) in zip(visited, expected):
        assert math.hypot(x - ex, y - ey) < 0.05
    assert len(visited) == 4


def test_ticker_keeps_its_schedule():
    ticks = []
    done = threading.Event()

    def tick():
        ticks.append(time.monotonic())
        if len(ticks) == 25:
            done.set()

    ticker = Ticker(0.01, tick)
    ticker.start()
    assert done.wait(5.0)
    ticker.stop()
    ticker.join(1.0)
    span = ticks[24] - ticks[0]
    assert span == pytest.approx(0.24, abs=0.1)
