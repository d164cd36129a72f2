"""Subscribers that remember what they saw, for assertions in milestone tests."""
from __future__ import annotations

import re
import threading
from typing import List, Optional

import rospy
from rosgraph_msgs.msg import Log


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

    def clear(self) -> None:
        with self._lock:
            self._messages.clear()

    def unregister(self) -> None:
        self.sub.unregister()


class RosoutRecorder(TopicRecorder):
    """The log lines nodes send to /rosout, searchable by regular expression."""

    def __init__(self) -> None:
        super().__init__("/rosout", Log)

    def matching(self, pattern: str, node: Optional[str] = None) -> List[Log]:
        regex = re.compile(pattern)
        return [m for m in self.messages
                if regex.search(m.msg) and (node is None or m.name.rstrip("/").endswith(node))]
