"""Real-time pacing: how long to sleep so simulated time advances at a given factor of wall time."""
from __future__ import annotations


class Pacer:
    """real_time_factor <= 0 means flat out (never sleep)."""

    def __init__(self, real_time_factor: float, wall_start: float, sim_start: float) -> None:
        self.factor = real_time_factor
        self.rebase(wall_start, sim_start)

    def rebase(self, wall: float, sim: float) -> None:
        """Start counting again (after a pause, a reset, or falling far behind)."""
        self._wall0, self._sim0 = wall, sim

    def delay(self, wall_now: float, sim_now: float) -> float:
        """Seconds to sleep before stepping on; rebases when more than 0.5 s behind."""
        if self.factor <= 0:
            return 0.0
        due = self._wall0 + (sim_now - self._sim0) / self.factor
        if wall_now - due > 0.5:
            self.rebase(wall_now, sim_now)
            return 0.0
        return max(0.0, due - wall_now)
