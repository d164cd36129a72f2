"""Forward every message from one topic to another without knowing its type.

The input is subscribed as rospy.AnyMsg (raw bytes, never deserialised). The output
publisher is created on the first message, with a message class carrying the type,
md5sum and definition read from the publisher's connection header, so subscribers of
the real type accept it. ~lazy (like topic_tools): once the output exists, the input
is only subscribed while the output has subscribers.
"""
from __future__ import annotations

import threading
from typing import Dict, Optional, Type

import rospy


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
    """IN -> OUT for any message type; optionally lazy."""

    def __init__(self, in_topic: str, out_topic: str, lazy: bool = False) -> None:
        self.in_topic, self.out_topic, self.lazy = in_topic, out_topic, lazy
        self._lock = threading.Lock()
        self._sub: Optional[rospy.Subscriber] = None
        self._pub: Optional[rospy.Publisher] = None
        self._out_class: Optional[Type[rospy.AnyMsg]] = None
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
        pub = self._pub
        if pub is None:
            pub = self._advertise(msg._connection_header)
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
                self._out_class = relay_class(header)
                listener = _LazyListener(self) if self.lazy else None
                # queue_size=None: publish synchronously from the subscriber thread (lowest latency)
                self._pub = rospy.Publisher(self.out_topic, self._out_class, queue_size=None,
                                            subscriber_listener=listener, tcp_nodelay=True)
            return self._pub
