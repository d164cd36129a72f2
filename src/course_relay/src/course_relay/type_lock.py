"""The message type a relay is locked onto, and when to warn about messages of other types.

topic_tools relay forwards the first type it sees on its input and never another one: a
message of another type (a second publisher on IN with another type) would reach OUT's
subscribers as bytes they misread. A type is its name and md5sum, both read from the
publisher's connection header. Pure logic, no rospy.
"""
from __future__ import annotations

import threading
from typing import Dict, Mapping, Optional, Tuple

MessageType = Tuple[str, str]  # (type name, md5sum)


def message_type(connection_header: Mapping[str, str]) -> MessageType:
    return connection_header.get("type", ""), connection_header.get("md5sum", "")


def describe(msg_type: MessageType) -> str:
    return "%s (md5sum %s)" % msg_type


class TypeLock:
    """Locks onto the first type offered; thread-safe (rospy calls back from one thread per publisher)."""

    def __init__(self, warning_period_s: float) -> None:
        self.warning_period_s = warning_period_s
        self.locked: Optional[MessageType] = None
        self._last_warning: Dict[MessageType, float] = {}
        self._lock = threading.Lock()

    def admits(self, connection_header: Mapping[str, str]) -> bool:
        """True for the locked type (locking onto this one if none is locked yet)."""
        offered = message_type(connection_header)
        with self._lock:
            if self.locked is None:
                self.locked = offered
            return offered == self.locked

    def warning_due(self, connection_header: Mapping[str, str], now: float) -> bool:
        """Whether to warn now about dropping this (other) type: at most once per period and type,
        so a third type is reported even while a second one keeps coming."""
        offered = message_type(connection_header)
        with self._lock:
            last = self._last_warning.get(offered)
            if last is not None and now - last < self.warning_period_s:
                return False
            self._last_warning[offered] = now
            return True
