"""Helpers for integration tests against a running turtlesim: wait for conditions, not for time."""
from __future__ import annotations

import threading
import time
from typing import Callable, List, Optional, Type

import rospy
from rosgraph_msgs.msg import Log


def wait_until(condition: Callable[[], bool], timeout: float = 5.0, period: float = 0.01) -> bool:
    """Poll `condition` until it holds or `timeout` seconds pass; returns whether it held."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(period)
    return bool(condition())


class Latest:
    """Keeps the latest message (and a count) of one topic."""

    def __init__(self, topic: str, msg_type: Type) -> None:
        self.msg = None
        self.count = 0
        self._lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, msg_type, self._on_msg, queue_size=10)

    def _on_msg(self, msg) -> None:
        with self._lock:
            self.msg = msg
            self.count += 1

    def wait(self, condition: Callable = lambda m: True, timeout: float = 5.0):
        """The first latest message that satisfies `condition`, or None after `timeout`."""
        found: List = []

        def check() -> bool:
            msg = self.msg
            if msg is not None and condition(msg):
                found.append(msg)
                return True
            return False

        return found[0] if wait_until(check, timeout) else None

    def close(self) -> None:
        self.sub.unregister()


class RosoutWatcher:
    """Collects /rosout messages, to assert that a node logged a warning or an error."""

    def __init__(self) -> None:
        self.messages: List[Log] = []
        self.sub = rospy.Subscriber("/rosout", Log, self.messages.append, queue_size=100)

    def wait_for(self, text: str, level: Optional[int] = None, timeout: float = 5.0) -> Optional[Log]:
        def match() -> Optional[Log]:
            for m in list(self.messages):
                if text in m.msg and (level is None or m.level == level):
                    return m
            return None
        return match() if wait_until(lambda: match() is not None, timeout) else None
