"""One client's bounded outgoing queue: what a slow viewer costs is its own dropped messages.

Every subscription of the client has its own queue of queue_length messages (the oldest is
dropped when it is full) and its own throttle_rate (the least time between two of its messages
going out). Replies (status, service_response) have a queue of their own, served first. The
sender takes messages round-robin across subscriptions, so a busy topic cannot starve a quiet
one. Producers are ROS callbacks on their own threads; nothing here blocks on the network.
Time is passed in (seconds, monotonic), so the module is pure and tests control the clock.
"""
from __future__ import annotations

import collections
import threading
from typing import Deque, Dict, Hashable, List, Optional, Tuple, Union

Payload = Union[str, bytes]

DEFAULT_QUEUE_LENGTH = 10
"""A subscription that asks for queue_length 0 (rosbridge's default: no throttling queue) still
keeps at most this many messages for a client that reads slower than they come."""
MAX_QUEUE_LENGTH = 1000
EARLY_S = 1e-3
"""A throttled message counts as due this much early (a timer may wake slightly before)."""
REPLY_QUEUE_LENGTH = 200
"""Replies beyond this (a client flooding bad requests and never reading) drop the oldest."""


class _Lane:
    def __init__(self, queue_length: int, throttle_s: float) -> None:
        self.queue: Deque[Payload] = collections.deque(maxlen=queue_length)
        self.throttle_s = throttle_s
        self.last_sent = -float("inf")
        self.dropped = 0


def lane_size(queue_length: int) -> int:
    """The bound a subscription's queue really gets for the queue_length it asked for."""
    return min(max(int(queue_length), 0), MAX_QUEUE_LENGTH) or DEFAULT_QUEUE_LENGTH


class Outbox:
    """See the module docstring. Thread-safe."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._replies: Deque[Payload] = collections.deque(maxlen=REPLY_QUEUE_LENGTH)
        self._lanes: Dict[Hashable, _Lane] = {}
        self._order: List[Hashable] = []
        self._next = 0

    def open_lane(self, key: Hashable, queue_length: int = 0, throttle_ms: float = 0.0) -> None:
        """A queue for one subscription (replacing the previous one of that key)."""
        with self._lock:
            if key not in self._lanes:
                self._order.append(key)
            self._lanes[key] = _Lane(lane_size(queue_length), max(float(throttle_ms), 0.0) / 1000.0)

    def close_lane(self, key: Hashable) -> None:
        with self._lock:
            if self._lanes.pop(key, None) is not None:
                self._order.remove(key)

    def put(self, key: Hashable, payload: Payload) -> bool:
        """Queue a message of a subscription. True when the sender must be woken: the lane was
        empty, so the sender may be asleep without knowing when this lane is due. False when the
        lane is gone (unsubscribed), or already held a message: the sender is then sending, or
        sleeping until that message (this lane's next slot) is due, and this one takes its place
        or follows it. A 62.5 Hz pose throttled to 20 Hz wakes the sender 20 times a second, not 62.5."""
        with self._lock:
            lane = self._lanes.get(key)
            if lane is None:
                return False
            was_empty = not lane.queue
            if len(lane.queue) == lane.queue.maxlen:
                lane.dropped += 1
            lane.queue.append(payload)
            return was_empty

    def reply(self, payload: Payload) -> None:
        """Queue a reply (status, service_response)."""
        with self._lock:
            self._replies.append(payload)

    def take(self, now: float) -> Optional[Payload]:
        """The next message due at `now`, or None."""
        with self._lock:
            if self._replies:
                return self._replies.popleft()
            count = len(self._order)
            for step in range(count):
                index = (self._next + step) % count
                lane = self._lanes[self._order[index]]
                if lane.queue and now - lane.last_sent >= lane.throttle_s - EARLY_S:
                    lane.last_sent = now
                    self._next = (index + 1) % count
                    return lane.queue.popleft()
            return None

    def next_due(self, now: float) -> Optional[float]:
        """Seconds until a queued message becomes due (0 when one is due now), None when empty."""
        with self._lock:
            if self._replies:
                return 0.0
            waits = [max(0.0, lane.last_sent + lane.throttle_s - EARLY_S - now)
                     for lane in self._lanes.values() if lane.queue]
            return min(waits) if waits else None

    def dropped(self) -> Dict[Hashable, int]:
        """Messages dropped per subscription because the client read too slowly."""
        with self._lock:
            return {key: lane.dropped for key, lane in self._lanes.items()}

    def pending(self) -> Tuple[int, int]:
        """(replies, subscription messages) waiting."""
        with self._lock:
            return len(self._replies), sum(len(lane.queue) for lane in self._lanes.values())
