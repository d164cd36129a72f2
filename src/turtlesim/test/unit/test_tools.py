"""The draw_square driver and the ticker schedule (turtle_teleop_key's keys: course_keyboard)."""
import math
import threading
import time

import pytest

from turtlesim.square import SquareDriver
from turtlesim.ticker import Ticker
from turtlesim.turtle import Turtle


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


def run_ticker(count, period, **options):
    """A Ticker run until it has ticked `count` times: (the tick times, the stopped ticker)."""
    ticks = []
    done = threading.Event()

    def tick():
        ticks.append(time.monotonic())
        if len(ticks) == count:
            done.set()

    ticker = Ticker(period, tick, **options)
    ticker.start()
    assert done.wait(5.0)
    ticker.stop()
    ticker.join(1.0)
    return ticks, ticker


def test_ticker_keeps_its_schedule():
    ticks, _ = run_ticker(25, 0.01)
    span = ticks[24] - ticks[0]
    assert span == pytest.approx(0.24, abs=0.1)


def test_ticker_stop_ends_a_long_wait_at_once_and_may_come_twice():
    ticker = Ticker(30.0, lambda: None)
    ticker.start()
    ticker.stop()
    ticker.stop()  # a second stop (another thread, a shutdown hook) is harmless
    ticker.join(2.0)
    assert not ticker.is_alive()


def test_a_batched_ticker_keeps_every_tick_with_fewer_wake_ups():
    ticks, ticker = run_ticker(40, 0.005, batch=lambda: 2)
    assert len(ticks) >= 40 and ticker.wakes <= len(ticks) // 2 + 1


def test_a_ticker_whose_batch_question_fails_ticks_once_a_wake_up():
    ticks, ticker = run_ticker(10, 0.005, batch=lambda: 1 // 0)
    assert ticker.wakes >= len(ticks) - 1


def test_a_late_wake_up_is_made_up_and_a_stall_restarts_the_schedule():
    period = 0.02
    stalls = {5: 3.5, 30: 40.0}  # tick number -> how many periods it takes
    ticks = []
    done = threading.Event()

    def tick():
        ticks.append(time.monotonic())
        time.sleep(stalls.get(len(ticks) - 1, 0.0) * period)
        if len(ticks) == 60:
            done.set()

    ticker = Ticker(period, tick)
    ticker.start()
    assert done.wait(10.0)
    ticker.stop()
    ticker.join(1.0)
    # 3.5 periods late after tick 5: made up (tick 25 keeps tick 0's schedule); 40 after tick 30: a restart
    assert ticks[25] - ticks[0] == pytest.approx(25 * period, abs=2.5 * period)
    assert ticker.late_restarts == 1
    assert ticks[45] - ticks[31] == pytest.approx(14 * period, abs=2.5 * period)  # no burst of 40 after it
