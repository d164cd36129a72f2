"""A drift-free periodic thread: the 16 ms heartbeat of the simulator."""
from __future__ import annotations

import threading
import time
from typing import Callable, Optional


class Ticker(threading.Thread):
    """Calls `tick()` every `period` seconds on an absolute schedule.

    Deadlines are start + k * period, so lateness in one tick does not shift the
    following ones; if the callback falls more than one period behind, the
    schedule restarts from now instead of bursting to catch up. An exception in `tick`
    goes to `on_error` and the heartbeat goes on: one bad tick must not stop the simulator.
    """

    def __init__(self, period: float, tick: Callable[[], None], name: str = "ticker",
                 on_error: Optional[Callable[[Exception], None]] = None) -> None:
        super().__init__(name=name, daemon=True)
        self.period = period
        self._tick = tick
        self._on_error = on_error
        self._halt = threading.Event()
        self.late_restarts = 0
        self.failed_ticks = 0

    def stop(self) -> None:
        self._halt.set()

    def run(self) -> None:
        deadline = time.monotonic() + self.period
        while not self._halt.is_set():
            delay = deadline - time.monotonic()
            if delay > 0 and self._halt.wait(delay):
                break
            try:
                self._tick()
            except Exception as err:  # noqa: BLE001  (whatever it was, the next tick must come)
                self.failed_ticks += 1
                if self._on_error is not None:
                    self._on_error(err)
            deadline += self.period
            if time.monotonic() - deadline > self.period:
                deadline = time.monotonic() + self.period
                self.late_restarts += 1
