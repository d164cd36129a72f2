"""A drift-free periodic thread: the 16 ms heartbeat of the simulator."""
from __future__ import annotations

import threading
import time
from typing import Callable, Optional


CATCH_UP_PERIODS = 4  # how late a wake-up may be and still be made up (64 ms at turtlesim's 16 ms)


class Ticker(threading.Thread):
    """Calls `tick()` every `period` seconds on an absolute schedule.

    Deadlines are start + k * period, so lateness in one tick does not shift the
    following ones. A wake-up up to CATCH_UP_PERIODS late (a busy machine's scheduling delay) is
    made up with ticks back to back, so the simulation keeps wall time (a turtle told 1 m/s goes
    1 m a second) and its 62.5 poses a second; further behind (a stopped process), the schedule
    restarts from now instead of bursting. An exception in `tick`
    goes to `on_error` and the heartbeat goes on: one bad tick must not stop the simulator.

    `batch()`, asked before each wait, may say to run more than one tick at a wake-up: the ticks
    keep their count and their schedule (each still one period of simulated time), only the
    wake-ups get fewer. turtlesim asks for two while nobody listens to a pose or a colour sensor, since
    a wake-up costs more CPU than a tick's work here.

    Between ticks it waits on a lock that only stop() releases: a timed acquire of one lock costs
    about 77 us of CPU a wake-up here, against 126 us for Event.wait (which makes a new lock and
    condition every call); at 62.5 Hz that is 0.3% of a core less, and stop() still ends the wait at once.
    """

    def __init__(self, period: float, tick: Callable[[], None], name: str = "ticker",
                 on_error: Optional[Callable[[Exception], None]] = None,
                 batch: Callable[[], int] = lambda: 1) -> None:
        super().__init__(name=name, daemon=True)
        self.period = period
        self._tick = tick
        self._on_error = on_error
        self._batch = batch
        self.wakes = 0
        self._halt = threading.Event()
        self._stopping = threading.Lock()  # stop() from two threads releases _wake once
        self._wake = threading.Lock()
        self._wake.acquire()  # held until stop(): the waits between ticks time out on it
        self.late_restarts = 0
        self.failed_ticks = 0

    def stop(self) -> None:
        with self._stopping:
            if not self._halt.is_set():
                self._halt.set()
                self._wake.release()

    def run(self) -> None:
        deadline = time.monotonic() + self.period
        while not self._halt.is_set():
            ticks = self._ticks_now()
            delay = deadline + (ticks - 1) * self.period - time.monotonic()
            if delay > 0 and self._wake.acquire(timeout=delay):
                break
            self.wakes += 1
            for _ in range(ticks):
                try:
                    self._tick()
                except Exception as err:  # noqa: BLE001  (whatever it was, the next tick must come)
                    self.failed_ticks += 1
                    if self._on_error is not None:
                        self._on_error(err)
                deadline += self.period
            if time.monotonic() - deadline > CATCH_UP_PERIODS * self.period:
                deadline = time.monotonic() + self.period
                self.late_restarts += 1

    def _ticks_now(self) -> int:
        """How many ticks the next wake-up runs: batch()'s answer, 1 when it has none to give."""
        try:
            return max(1, int(self._batch()))
        except Exception:  # noqa: BLE001  (a question about the next wake-up must not stop the heartbeat)
            return 1
