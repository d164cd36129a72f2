"""Forward every message from one topic to another without knowing its type.

The input is subscribed as rospy.AnyMsg (raw bytes, never deserialised). The output
publisher is created on the first message, with a message class carrying the type,
md5sum and definition read from the publisher's connection header, so subscribers of
the real type accept it. As topic_tools relay does:
- the output is latched when the first message came from a latched publisher (its
  "latching" header), so a one-shot `rostopic pub -1` still reaches later subscribers;
- the relay keeps the first type it saw: a message of another type (a second publisher of
  another type on IN) is dropped, with a throttled warning naming both types, never sent
  out as bytes that the output's subscribers would misread;
- ~lazy: once the output exists, the input is only subscribed while the output has
  subscribers.
"""
from __future__ import annotations

import threading
import time
from typing import Dict, Optional, Type

import rospy

from course_relay.type_lock import TypeLock, describe, message_type

#: Messages the output may hold per subscriber before rospy drops the oldest (topic_tools: 10).
OUT_QUEUE_SIZE = 10
#: Seconds between two warnings about messages of the same other type.
TYPE_WARNING_PERIOD_S = 5.0


def relay_class(connection_header: Dict[str, str]) -> Type[rospy.AnyMsg]:
    """An AnyMsg subclass that announces the original type (so publishers can advertise it)."""
    msg_type = connection_header["type"]
    return type("Relayed_" + msg_type.replace("/", "_"), (rospy.AnyMsg,), {
        "_type": msg_type,
        "_md5sum": connection_header["md5sum"],
        "_full_text": connection_header.get("message_definition", ""),
        "_has_header": False,
        "__slots__": [],
    })


def is_latched(connection_header: Dict[str, str]) -> bool:
    """Whether the publisher of a message latches it (rospy and roscpp send latching=1)."""
    return connection_header.get("latching") == "1"


class _LazyListener(rospy.SubscribeListener):
    def __init__(self, relay: "TopicRelay") -> None:
        super().__init__()
        self.relay = relay

    def peer_subscribe(self, topic_name, topic_publish, peer_publish) -> None:
        self.relay.subscribe_input()

    def peer_unsubscribe(self, topic_name, num_peers) -> None:
        if num_peers == 0:
            self.relay.unsubscribe_input()


class TopicRelay:
    """IN -> OUT for any message type (the first one seen); optionally lazy."""

    def __init__(self, in_topic: str, out_topic: str, lazy: bool = False) -> None:
        """Names as given on the command line (already checked); resolved here like rospy would."""
        self.in_topic, self.out_topic = rospy.resolve_name(in_topic), rospy.resolve_name(out_topic)
        self.lazy = lazy
        self._lock = threading.Lock()
        self._sub: Optional[rospy.Subscriber] = None
        self._pub: Optional[rospy.Publisher] = None
        self._out_class: Optional[Type[rospy.AnyMsg]] = None
        self._types = TypeLock(TYPE_WARNING_PERIOD_S)
        self.subscribe_input()

    def subscribe_input(self) -> None:
        with self._lock:
            if self._sub is None:
                self._sub = rospy.Subscriber(self.in_topic, rospy.AnyMsg, self._forward,
                                             queue_size=100, tcp_nodelay=True)

    def unsubscribe_input(self) -> None:
        with self._lock:
            if self.lazy and self._sub is not None and self._pub is not None:
                self._sub.unregister()
                self._sub = None

    def _forward(self, msg: rospy.AnyMsg) -> None:
        header = msg._connection_header
        pub = self._pub
        if pub is None:
            pub = self._advertise(header)
        if not self._types.admits(header):
            if self._types.warning_due(header, time.monotonic()):
                rospy.logwarn("relay %s -> %s: dropping %s messages from %s: the relay forwards %s, the first "
                              "type it saw on %s" % (self.in_topic, self.out_topic, describe(message_type(header)),
                                                     header.get("callerid"), describe(self._types.locked),
                                                     self.in_topic))
            return
        out = self._out_class()
        out._buff = msg._buff
        try:
            pub.publish(out)
        except rospy.ROSException:
            pass  # shutting down
        if self.lazy and pub.get_num_connections() == 0:
            self.unsubscribe_input()

    def _advertise(self, header: Dict[str, str]) -> rospy.Publisher:
        with self._lock:
            if self._pub is None:
                self._types.admits(header)  # lock onto the type we advertise, before any other thread can
                self._out_class = relay_class(header)
                listener = _LazyListener(self) if self.lazy else None
                self._pub = rospy.Publisher(self.out_topic, self._out_class, queue_size=OUT_QUEUE_SIZE,
                                            latch=is_latched(header), subscriber_listener=listener,
                                            tcp_nodelay=True)
            return self._pub
