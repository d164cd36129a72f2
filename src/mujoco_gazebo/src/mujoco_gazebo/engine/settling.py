"""When is a joint-controlled robot still? Not when one joint_states sample shows a small
velocity: RRBot on its P-D position servos swings about its target for seconds (period about
0.8 s), and every swing passes through zero velocity at its turning points, while its
camera still moves centimetres. Still means: every sample over a window longer than a swing
is slow. Used by the camera test (its "still arm, same picture" check was flaky because of
this) and unit-tested against the simulated arm."""
from __future__ import annotations

from collections import deque
from typing import Deque, Sequence, Tuple

STILL_WINDOW_S = 1.0     # simulated seconds; longer than RRBot's swing
STILL_SPEED = 0.005      # rad/s (or m/s), every joint


class StillnessDetector:
    """Feed joint_states samples (sim time, velocities); `still` once a full window is slow."""

    def __init__(self, window: float = STILL_WINDOW_S, speed: float = STILL_SPEED) -> None:
        self.window, self.speed = window, speed
        self._samples: Deque[Tuple[float, bool]] = deque()

    def add(self, stamp: float, velocities: Sequence[float]) -> None:
        if self._samples and stamp < self._samples[-1][0]:
            self._samples.clear()  # time went back (a reset): start over
        self._samples.append((stamp, all(abs(v) < self.speed for v in velocities)))
        while len(self._samples) > 1 and self._samples[1][0] <= stamp - self.window:
            self._samples.popleft()

    @property
    def still(self) -> bool:
        if not self._samples or self._samples[-1][0] - self._samples[0][0] < self.window:
            return False
        return all(slow for _, slow in self._samples)
