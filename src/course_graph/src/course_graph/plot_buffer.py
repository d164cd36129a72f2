"""The samples rqt_plot draws: a (time, value) series per field path.

Subscriber callbacks add samples from rospy's threads while the drawing reads them, so every
access holds a lock. A live window only shows the last seconds, so it can keep just those.
"""
from __future__ import annotations

import threading
from typing import Dict, List, Optional, Sequence, Tuple

Series = Tuple[List[float], List[float]]


class SampleBuffer:
    """Times (seconds since the start of the recording) and values, one series per label,
    in the order the labels were given (that order picks the line colours)."""

    def __init__(self, labels: Sequence[str], keep_seconds: Optional[float] = None) -> None:
        self._series: Dict[str, Series] = {label: ([], []) for label in labels}
        self._keep_seconds = keep_seconds
        self._lock = threading.Lock()

    @property
    def labels(self) -> List[str]:
        return list(self._series)

    def add(self, label: str, time: float, value: float) -> None:
        """One sample; with keep_seconds, samples older than that before this one are dropped."""
        with self._lock:
            times, values = self._series[label]
            times.append(time)
            values.append(value)
            if self._keep_seconds is not None:
                oldest = time - self._keep_seconds
                drop = next((i for i, t in enumerate(times) if t >= oldest), len(times))
                del times[:drop]
                del values[:drop]

    def snapshot(self) -> Dict[str, Series]:
        """A copy of every series, safe to draw while samples keep coming."""
        with self._lock:
            return {label: (list(times), list(values)) for label, (times, values) in self._series.items()}

    def count(self, label: str) -> int:
        with self._lock:
            return len(self._series[label][0])

    def empty_labels(self) -> List[str]:
        """The labels without any sample yet."""
        with self._lock:
            return [label for label, (times, _) in self._series.items() if not times]
