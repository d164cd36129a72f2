"""Subscribers that remember what they saw, for assertions in milestone tests."""
from __future__ import annotations

import re
import threading
from typing import Callable, List, Optional

import rospy
from rosgraph_msgs.msg import Log

from course_checks.waiting import wait_for


class TopicRecorder:
    """Keeps every message received on a topic (thread-safe snapshot via .messages)."""

    def __init__(self, topic: str, msg_type, tcp_nodelay: bool = True) -> None:
        self._lock = threading.Lock()
        self._messages: List = []
        self.sub = rospy.Subscriber(topic, msg_type, self._on_msg, tcp_nodelay=tcp_nodelay)

    def _on_msg(self, msg) -> None:
        with self._lock:
            self._messages.append(msg)

    @property
    def messages(self) -> List:
        with self._lock:
            return list(self._messages)

    @property
    def last(self):
        with self._lock:
            return self._messages[-1] if self._messages else None

    @property
    def count(self) -> int:
        with self._lock:
            return len(self._messages)

    def wait(self, condition: Callable = lambda m: True, timeout: float = 5.0):
        """The newest message satisfying `condition` once one arrives, or None after `timeout`."""
        def newest_match():
            last = self.last
            return last if last is not None and condition(last) else None
        return wait_for(newest_match, timeout)

    def clear(self) -> None:
        with self._lock:
            self._messages.clear()

    def unregister(self) -> None:
        self.sub.unregister()


class RosoutRecorder(TopicRecorder):
    """The log lines nodes send to /rosout, searchable by regular expression."""

    def __init__(self) -> None:
        super().__init__("/rosout", Log)

    def matching(self, pattern: str, node: Optional[str] = None, level: Optional[int] = None) -> List[Log]:
        """Log lines whose text matches `pattern` (optionally from `node`, at `level`, e.g. Log.WARN)."""
        regex = re.compile(pattern)
        return [m for m in self.messages
                if regex.search(m.msg) and (node is None or m.name.rstrip("/").endswith(node))
                and (level is None or m.level == level)]

    def wait_for_text(self, text: str, level: Optional[int] = None, timeout: float = 5.0) -> List[Log]:
        """Wait until a line containing `text` (literally) is logged; the matching lines, or []."""
        return wait_for(lambda: self.matching(re.escape(text), level=level), timeout)
