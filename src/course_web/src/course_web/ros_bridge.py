"""The ROS side of the bridge: shared publishers and subscribers, service calls, type checks.

However many clients watch a topic, the node holds one rospy.Subscriber for it and turns each
message into its publish frame (or compressed picture) once, then hands the same payload to
every client's outbox: the ROS callback never waits for a client. Publishers are shared the
same way. Each service call runs on a thread of its own (a client may have only a few waiting, see
course_web.protocol), so a service that never answers delays only its caller's reply. Types come from the request, or from the master when the request leaves them out, and a
request that contradicts the master (another type on the same topic) is refused, because rospy
would otherwise connect nothing and say nothing. A service's type, which the master does not know,
is asked of the service itself (course_web.service_probe: rosservice's probe without importing
rosservice).
"""
from __future__ import annotations

import http.client
import threading
import xmlrpc.client
from typing import Any, Dict, Hashable, Optional, Set, Tuple, Type

import genpy
import rosgraph
import rospy

from course_net.rpc import TimedTransport
from course_web import frames, service_probe
from course_web.introspect import ApiError
from course_web.convert import ConversionError, json_to_message, message_class, message_to_json, service_class
from course_web.protocol import Bridge, Deliver, RequestError, ServiceDone, publish_frame

IMAGE_TYPE = "sensor_msgs/Image"
CALLER_ID = "/course_web"
NODE_TIMEOUT_S = 1.0  # a node's XML-RPC answer to getPid (the page's health asks the canvas's publishers)
MASTER_TIMEOUT_S = 5.0
SERVICE_PROBE_TIMEOUT_S = 5.0  # a service's node asked its type (rosservice's own timeout)
SUBSCRIBER_QUEUE = 10


def required_class(type_name: str) -> Type[genpy.Message]:
    cls = message_class(type_name) if "/" in type_name else None
    if cls is None:
        raise RequestError("unknown message type %r" % type_name)
    return cls


class _Publisher:
    def __init__(self, type_name: str, cls: Type[genpy.Message], publisher: rospy.Publisher) -> None:
        self.type_name, self.cls, self.publisher = type_name, cls, publisher
        self.clients: Set[Hashable] = set()


class _Feed:
    """One topic's rospy.Subscriber and the clients it feeds.

    The feed keeps each latching publisher's last message: rospy hands it over only when the
    subscriber connects, so a client that joins a shared feed later (a second page watching
    /tf_static) gets it from here, as it would from a subscriber of its own."""

    def __init__(self, topic: str, type_name: str, cls: Type[genpy.Message]) -> None:
        self.topic, self.type_name = topic, type_name
        self.lock = threading.Lock()
        self.readers: Dict[Hashable, Tuple[Optional[str], Deliver]] = {}
        self.latched: Dict[str, genpy.Message] = {}  # publisher's caller id -> its last message
        self.subscriber = rospy.Subscriber(topic, cls, self.on_message, queue_size=SUBSCRIBER_QUEUE)

    def add_reader(self, key: Hashable, compression: Optional[str], deliver: Deliver) -> None:
        with self.lock:
            self.readers[key] = (compression, deliver)
            replay = list(self.latched.values())
        for msg in replay:
            payload = self.encoded(msg, compression)
            if payload is not None:
                deliver(payload)

    def on_message(self, msg: genpy.Message) -> None:
        header = getattr(msg, "_connection_header", None) or {}
        with self.lock:
            if header.get("latching") == "1":
                self.latched[header.get("callerid", "")] = msg
            readers = list(self.readers.values())
        encoded: Dict[Optional[str], Any] = {}
        for compression, deliver in readers:
            if compression not in encoded:
                encoded[compression] = self.encoded(msg, compression)
            if encoded[compression] is not None:
                deliver(encoded[compression])

    def encoded(self, msg: genpy.Message, compression: Optional[str]) -> Any:
        """The payload for a reader asking `compression`, or None (with a throttled warning)."""
        try:
            return self.encode(msg, compression)
        except (ValueError, TypeError) as err:
            rospy.logwarn_throttle(5.0, "lab_view: %s: cannot send a message: %s" % (self.topic, err))
            return None

    def encode(self, msg: genpy.Message, compression: Optional[str]):
        if compression is None:
            return publish_frame(self.topic, message_to_json(msg))
        stamp = {"secs": msg.header.stamp.secs, "nsecs": msg.header.stamp.nsecs}
        return frames.image_frame(self.topic, compression, msg.encoding, msg.width, msg.height, msg.step,
                                  msg.data, stamp)


class RosBridge(Bridge):
    """The Bridge of course_web.protocol, wired to rospy (the node must be initialised)."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.publishers: Dict[str, _Publisher] = {}
        self.feeds: Dict[str, _Feed] = {}
        self.master = RosMaster()

    def topic_type(self, topic: str) -> Optional[str]:
        """The topic's type as the master knows it (None: nobody publishes or subscribes it)."""
        try:
            return self.master.topic_types().get(topic)
        except ApiError as err:
            raise RequestError(str(err))

    def _checked_type(self, topic: str, type_name: Optional[str]) -> str:
        known = self.topic_type(topic)
        if not type_name:
            if known is None:
                raise RequestError("unknown topic %s: no node publishes it and no type was given" % topic)
            return known
        if known is not None and known != type_name:
            raise RequestError("type mismatch: %s has type %s, not %s" % (topic, known, type_name))
        return type_name

    # -- topics out -----------------------------------------------------------------------
    def advertise(self, client: Hashable, topic: str, type_name: str, latch: bool, queue_size: int) -> None:
        with self.lock:
            current = self.publishers.get(topic)
            if current is not None:
                if type_name and type_name != current.type_name:
                    raise RequestError("type mismatch: %s is advertised as %s, not %s" % (topic, current.type_name, type_name))
                current.clients.add(client)
                return
        type_name = self._checked_type(topic, type_name)
        cls = required_class(type_name)
        with self.lock:
            current = self.publishers.get(topic)
            if current is None:
                publisher = rospy.Publisher(topic, cls, queue_size=min(max(queue_size, 1), 1000), latch=latch)
                current = self.publishers[topic] = _Publisher(type_name, cls, publisher)
            current.clients.add(client)

    def unadvertise(self, client: Hashable, topic: str) -> None:
        with self.lock:
            current = self.publishers.get(topic)
            if current is None:
                return
            current.clients.discard(client)
            if current.clients:
                return
            del self.publishers[topic]
        current.publisher.unregister()

    def publish(self, client: Hashable, topic: str, msg: Any) -> None:
        with self.lock:
            current = self.publishers.get(topic)
        if current is None:
            raise RequestError("%s is not advertised" % topic)
        try:
            message = json_to_message(msg, current.cls, message_class)
        except ConversionError as err:
            raise RequestError("%s (%s): %s" % (topic, current.type_name, err))
        current.publisher.publish(message)

    # -- topics in ------------------------------------------------------------------------
    def subscribe(self, client: Hashable, key: Hashable, topic: str, type_name: Optional[str],
                  compression: Optional[str], deliver: Deliver) -> str:
        with self.lock:
            feed = self.feeds.get(topic)
        if feed is None:
            type_name = self._checked_type(topic, type_name)
        elif type_name and type_name != feed.type_name:
            raise RequestError("type mismatch: %s has type %s, not %s" % (topic, feed.type_name, type_name))
        else:
            type_name = feed.type_name
        if compression is not None and type_name != IMAGE_TYPE:
            raise RequestError("compression %s is for %s topics; %s is %s" % (compression, IMAGE_TYPE, topic, type_name))
        cls = required_class(type_name)
        with self.lock:
            feed = self.feeds.get(topic)
            if feed is None:
                feed = self.feeds[topic] = _Feed(topic, type_name, cls)
            feed.add_reader(key, compression, deliver)  # under the lock: unsubscribe may be ending this feed
        return type_name

    def unsubscribe(self, client: Hashable, key: Hashable) -> None:
        with self.lock:
            for topic, feed in list(self.feeds.items()):
                with feed.lock:
                    if feed.readers.pop(key, None) is None or feed.readers:
                        continue
                del self.feeds[topic]
                feed.subscriber.unregister()

    # -- services -------------------------------------------------------------------------
    def call_service(self, service: str, type_name: Optional[str], args: Any, done: ServiceDone) -> None:
        threading.Thread(target=self._call, args=(service, type_name, args, done), daemon=True,
                         name="lab_view-call %s" % service[:40]).start()

    def _call(self, service: str, type_name: Optional[str], args: Any, done: ServiceDone) -> None:
        try:
            values = self._call_values(service, type_name, args)
        except (RequestError, ConversionError, rospy.ServiceException, rospy.ROSException, OSError) as err:
            done(False, str(err))
        except Exception as err:  # noqa: BLE001 - a reply is owed whatever went wrong
            done(False, "%s: %r" % (service, err))
        else:
            done(True, values)

    def _call_values(self, service: str, type_name: Optional[str], args: Any) -> Dict[str, Any]:
        if not type_name:
            type_name = self.service_type(service)
        cls = service_class(type_name)
        if cls is None:
            raise RequestError("unknown service type %r" % type_name)
        request_cls = cls._request_class
        if isinstance(args, list):
            if len(args) > len(request_cls.__slots__):
                raise RequestError("%s takes %d arguments, got %d" % (type_name, len(request_cls.__slots__), len(args)))
            args = dict(zip(request_cls.__slots__, args))
        request = json_to_message(args, request_cls, message_class)
        response = rospy.ServiceProxy(service, cls)(request)
        return message_to_json(response)

    def service_type(self, service: str) -> str:
        """The type the service's node says it has (raises RequestError when no node provides it,
        service_probe.ServiceProbeError when the node does not answer)."""
        try:
            uri = self.master.service_uri(service)
        except ApiError as err:
            raise RequestError(str(err))
        if uri is None:
            raise RequestError("unknown service %s" % service)
        return service_probe.service_type(service, uri, CALLER_ID, SERVICE_PROBE_TIMEOUT_S)

    def shutdown(self) -> None:
        """Nothing to wait for: a call still running is on a daemon thread."""


class RosMaster:
    """course_web.introspect's Master, asked over XML-RPC (a proxy per call: they are not thread-safe),
    each call given up after MASTER_TIMEOUT_S (a master stopped with SIGSTOP must not hang the page's
    watch). A node's address is asked of the master once and kept while the node answers there."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._addresses: Dict[str, str] = {}  # node -> its XML-RPC URI, as the master last said

    def _call(self, question: str, *args: Any) -> Tuple[str, int, str, Any]:
        """(the master's URI, and its code, message and value for `question`)."""
        uri = rosgraph.get_master_uri()
        try:
            proxy = xmlrpc.client.ServerProxy(uri, transport=TimedTransport(MASTER_TIMEOUT_S))
            code, message, value = getattr(proxy, question)(CALLER_ID, *args)
        except (OSError, xmlrpc.client.Error, http.client.HTTPException, ValueError, TypeError) as err:
            raise ApiError("the ROS master at %s does not answer: %s" % (uri, err), 503)
        return uri, code, message, value

    def _ask(self, question: str, *args: Any) -> Any:
        uri, code, message, value = self._call(question, *args)
        if code != 1:
            raise ApiError("the ROS master at %s refused %s: %s" % (uri, question, message), 503)
        return value

    def service_uri(self, service: str) -> Optional[str]:
        """The service's rosrpc:// address, or None when no node provides it."""
        _uri, code, _message, value = self._call("lookupService", service)
        return value if code == 1 and value else None

    def system_state(self) -> Any:
        return self._ask("getSystemState")

    def topic_types(self) -> Dict[str, str]:
        return dict(self._ask("getTopicTypes"))

    def node_answers(self, name: str) -> bool:
        """Whether the node answers at the address its master has for it: a node killed by a signal
        rospy does not catch (SIGKILL; SIGHUP, a closed terminal's) stays registered, silent. The
        address kept from before is tried first; when nothing answers there, the master is asked
        again (the node may have started again elsewhere under the same name)."""
        with self._lock:
            known = self._addresses.get(name)
        if known is not None and self._pid_answers(known):
            return True
        try:
            uri = self._ask("lookupNode", name)
        except ApiError:
            return False
        answers = uri != known and self._pid_answers(uri)
        with self._lock:
            if answers:
                self._addresses[name] = uri
            else:
                self._addresses.pop(name, None)
        return answers

    @staticmethod
    def _pid_answers(uri: str) -> bool:
        try:
            code, _message, _pid = xmlrpc.client.ServerProxy(uri, transport=TimedTransport(NODE_TIMEOUT_S)).getPid(
                CALLER_ID)
        except (OSError, xmlrpc.client.Error, http.client.HTTPException, ValueError):
            return False
        return code == 1
