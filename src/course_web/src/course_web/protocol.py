"""The rosbridge v2 protocol, one client's side of it, apart from ROS and the network.

A Session reads the client's text frames (JSON objects with an "op"), checks them and asks a
Bridge (the ROS wiring, or a fake in tests) to act; everything it says back goes into the
client's Outbox. Ops: advertise, unadvertise, publish, subscribe (throttle_rate, queue_length,
and our "compression": "jpeg" | "png" for sensor_msgs/Image, sent as binary frames),
unsubscribe, call_service (answered by service_response with values and result). Whatever goes
wrong with one request (bad JSON, an unknown op, topic, type or service, a field of the wrong
type, a message over the size limit) becomes a status message with level "error" and the
request's id, to this client only.

One op is the page's own, beyond rosbridge v2: lab_status ({"op": "lab_status", "health": topic,
"graph": true, "debug": false, "topics": true}; each field optional, a request replaces the
client's previous one, and one asking nothing ends it). The server then sends {"op":
"lab_status", <part>: <answer>} frames, each part at once and again only when it changes (see
course_web.lab_status), each part in a queue of one (only the newest answer matters). A rosbridge
client (roslibpy, roslibjs) never sends it, so it never receives any.
"""
from __future__ import annotations

import json
import threading
from typing import Any, Callable, Dict, Hashable, Optional, Protocol, Set, Tuple

from course_web.lab_status import Deliver as StatusDeliver, Wants
from course_web.outbox import Outbox, Payload

DEFAULT_MAX_MESSAGE_BYTES = 10 * 1024 * 1024
MAX_CALLS_IN_FLIGHT = 8
"""Service calls one client may have waiting for their replies; more are refused, so a client
calling a service that never answers holds up its own calls only."""
IMAGE_COMPRESSIONS = ("jpeg", "png")
MAX_HEALTH_TOPIC_CHARS = 1000
PLAIN_COMPRESSIONS = ("none", "", None)

Deliver = Callable[[Payload], None]
ServiceDone = Callable[[bool, Any], None]


class RequestError(Exception):
    """A request the bridge cannot carry out; the text goes to the client as a status error."""


class Bridge:
    """What a Session needs from ROS. Every method may raise RequestError (or ValueError)."""

    def advertise(self, client: Hashable, topic: str, type_name: str, latch: bool, queue_size: int) -> None:
        raise NotImplementedError

    def unadvertise(self, client: Hashable, topic: str) -> None:
        raise NotImplementedError

    def publish(self, client: Hashable, topic: str, msg: Any) -> None:
        raise NotImplementedError

    def subscribe(self, client: Hashable, key: Hashable, topic: str, type_name: Optional[str],
                  compression: Optional[str], deliver: Deliver) -> str:
        """Start delivering the topic's messages (already encoded) to `deliver`; the type used."""
        raise NotImplementedError

    def unsubscribe(self, client: Hashable, key: Hashable) -> None:
        raise NotImplementedError

    def call_service(self, service: str, type_name: Optional[str], args: Any, done: ServiceDone) -> None:
        """Start the call; done(result, values) later, from any thread."""
        raise NotImplementedError


class StatusSource(Protocol):
    """What a Session needs for the lab_status op (course_web.lab_status.LabStatus is one)."""

    def watch(self, client: Hashable, wants: Wants, deliver: StatusDeliver) -> None:
        """Tell `client` what it wants, now and on each change, by deliver(part, frame)."""

    def unwatch(self, client: Hashable) -> None:
        """Tell `client` nothing more."""


def encode(message: Dict[str, Any]) -> str:
    """A protocol message as the text frame that carries it (strict JSON: no NaN)."""
    return json.dumps(message, separators=(",", ":"), allow_nan=False)


def status(text: str, request_id: Optional[str] = None, level: str = "error") -> str:
    message = {"op": "status", "level": level, "msg": text}
    if request_id is not None:
        message["id"] = request_id
    return encode(message)


def publish_frame(topic: str, msg: Dict[str, Any]) -> str:
    """The publish op that carries a topic's message to a subscriber."""
    return encode({"op": "publish", "topic": topic, "msg": msg})


def service_response(service: str, request_id: Optional[str], result: bool, values: Any) -> str:
    message = {"op": "service_response", "service": service, "result": bool(result), "values": values}
    if request_id is not None:
        message["id"] = request_id
    return encode(message)


def _field(request: Dict[str, Any], name: str, kind: type, default: Any = None, required: bool = False) -> Any:
    if name not in request or request[name] is None:
        if required:
            raise RequestError("%s needs a \"%s\" field" % (request.get("op"), name))
        return default
    value = request[name]
    if kind is float and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    if not isinstance(value, kind) or (kind is int and isinstance(value, bool)):
        raise RequestError("%s: \"%s\" must be %s" % (request.get("op"), name, {
            str: "a string", int: "an integer", float: "a number", bool: "true or false"}.get(kind, kind.__name__)))
    return value


def _name(request: Dict[str, Any], field: str) -> str:
    name = _field(request, field, str, required=True)
    if not name or any(c.isspace() for c in name):
        raise RequestError("%s: \"%s\" is not a ROS name: %r" % (request.get("op"), field, name))
    return name if name.startswith("/") else "/" + name


class Session:
    """One websocket client's protocol state; see the module docstring."""

    def __init__(self, client: Hashable, bridge: Bridge, outbox: Outbox,
                 max_message_bytes: int = DEFAULT_MAX_MESSAGE_BYTES, wake: Callable[[], None] = lambda: None,
                 status: Optional[StatusSource] = None) -> None:
        self.client = client
        self.bridge = bridge
        self.status = status
        self.status_parts: Set[str] = set()  # the lab_status parts this client is told
        self.outbox = outbox
        self.max_message_bytes = max_message_bytes
        self.wake = wake
        self.advertised: Set[str] = set()
        self.subscriptions: Dict[Tuple[str, Optional[str]], str] = {}  # (topic, id) -> type
        # handle() and close() may run on different threads (the socket closes while a request
        # is still being handled): one at a time, and nothing is handled after close().
        self._lock = threading.Lock()
        self.closed = False
        self._calls_lock = threading.Lock()  # done() comes from the bridge's threads
        self.calls_in_flight = 0

    # -- replies ---------------------------------------------------------------------------
    def reply(self, payload: Payload) -> None:
        self.outbox.reply(payload)
        self.wake()

    def error(self, text: str, request_id: Optional[str] = None) -> None:
        self.reply(status(text, request_id))

    # -- requests --------------------------------------------------------------------------
    def handle(self, frame: Any) -> None:
        """One incoming frame (str or bytes): act on it or say why not."""
        with self._lock:
            if not self.closed:
                self._handle(frame)

    def _handle(self, frame: Any) -> None:
        if len(frame) > self.max_message_bytes:
            self.error("message of %d bytes refused: the limit is %d bytes" % (len(frame), self.max_message_bytes))
            return
        try:
            request = json.loads(frame)
        except (ValueError, UnicodeDecodeError) as err:
            self.error("malformed JSON: %s" % err)
            return
        if not isinstance(request, dict):
            self.error("a request must be a JSON object with an \"op\" field")
            return
        request_id = request.get("id")
        request_id = request_id if isinstance(request_id, str) or request_id is None else str(request_id)
        op = request.get("op")
        handler = self.HANDLERS.get(op) if isinstance(op, str) else None
        if handler is None:
            self.error("unknown op %r (this server knows: %s)" % (op, ", ".join(sorted(self.HANDLERS))), request_id)
            return
        try:
            handler(self, request, request_id)
        except (RequestError, ValueError) as err:
            self.error("%s: %s" % (op, err) if not str(err).startswith(op) else str(err), request_id)
        except Exception as err:  # noqa: BLE001 - one request's failure must not end the session
            self.error("%s failed inside the server: %r" % (op, err), request_id)

    def _advertise(self, request: Dict[str, Any], request_id: Optional[str]) -> None:
        topic = _name(request, "topic")
        type_name = _field(request, "type", str, required=True)
        latch = _field(request, "latch", bool, False)
        queue_size = _field(request, "queue_size", int, 100)
        self.bridge.advertise(self.client, topic, type_name, latch, queue_size)
        self.advertised.add(topic)

    def _unadvertise(self, request: Dict[str, Any], request_id: Optional[str]) -> None:
        topic = _name(request, "topic")
        if topic not in self.advertised:
            raise RequestError("%s is not advertised by this client" % topic)
        self.advertised.discard(topic)
        self.bridge.unadvertise(self.client, topic)

    def _publish(self, request: Dict[str, Any], request_id: Optional[str]) -> None:
        topic = _name(request, "topic")
        msg = request.get("msg", {})
        if topic not in self.advertised:
            type_name = _field(request, "type", str)
            self.bridge.advertise(self.client, topic, type_name or "", False, 100)
            self.advertised.add(topic)
        self.bridge.publish(self.client, topic, msg)

    def _subscribe(self, request: Dict[str, Any], request_id: Optional[str]) -> None:
        topic = _name(request, "topic")
        type_name = _field(request, "type", str)
        compression = _field(request, "compression", str, "none")
        if compression not in PLAIN_COMPRESSIONS + IMAGE_COMPRESSIONS:
            raise RequestError("compression %r is not supported (none, %s)" % (compression, ", ".join(IMAGE_COMPRESSIONS)))
        throttle = _field(request, "throttle_rate", float, 0.0)
        queue_length = _field(request, "queue_length", int, 0)
        if throttle < 0 or queue_length < 0:
            raise RequestError("throttle_rate and queue_length must not be negative")
        key = (topic, request_id)
        if key in self.subscriptions:
            self.bridge.unsubscribe(self.client, (self.client, key))
        lane = (self.client, key)
        self.outbox.open_lane(lane, queue_length, throttle)

        def deliver(payload: Payload) -> None:
            if self.outbox.put(lane, payload):
                self.wake()
        try:
            self.subscriptions[key] = self.bridge.subscribe(self.client, lane, topic, type_name,
                                                            None if compression in PLAIN_COMPRESSIONS else compression,
                                                            deliver)
        except BaseException:
            self.outbox.close_lane(lane)
            self.subscriptions.pop(key, None)
            raise

    def _unsubscribe(self, request: Dict[str, Any], request_id: Optional[str]) -> None:
        topic = _name(request, "topic")
        keys = [key for key in self.subscriptions
                if key[0] == topic and (request_id is None or key[1] == request_id)]
        if not keys:
            raise RequestError("no subscription to %s%s" % (topic, "" if request_id is None else " with id %s" % request_id))
        for key in keys:
            self._drop_subscription(key)

    def _drop_subscription(self, key: Tuple[str, Optional[str]]) -> None:
        del self.subscriptions[key]
        self.bridge.unsubscribe(self.client, (self.client, key))
        self.outbox.close_lane((self.client, key))

    def _call_service(self, request: Dict[str, Any], request_id: Optional[str]) -> None:
        service = _name(request, "service")
        type_name = _field(request, "type", str)
        args = request.get("args", {})
        if args is None:
            args = {}
        if not isinstance(args, (dict, list)):
            raise RequestError("call_service: \"args\" must be an object or a list")

        with self._calls_lock:
            if self.calls_in_flight >= MAX_CALLS_IN_FLIGHT:
                raise RequestError("call_service %s: %d calls of this client are still waiting for their "
                                   "replies; wait for one before calling again" % (service, self.calls_in_flight))
            self.calls_in_flight += 1
        settled = []

        def settle() -> bool:
            """Stop counting this call as waiting; True only the first time (a bridge may answer twice)."""
            with self._calls_lock:
                if settled:
                    return False
                settled.append(True)
                self.calls_in_flight -= 1
                return True

        def done(result: bool, values: Any) -> None:
            if not settle():
                return  # the first answer stands
            if not result:
                self.error("call_service %s: %s" % (service, values), request_id)
            self.reply(service_response(service, request_id, result, values))
        try:
            self.bridge.call_service(service, type_name, args, done)
        except BaseException:
            settle()
            raise

    def _lab_status(self, request: Dict[str, Any], request_id: Optional[str]) -> None:
        health = _field(request, "health", str)
        if health is not None and len(health) > MAX_HEALTH_TOPIC_CHARS:
            raise RequestError("lab_status: \"health\" is a topic name of %d characters (at most %d)"
                               % (len(health), MAX_HEALTH_TOPIC_CHARS))
        wants = Wants(health, _field(request, "graph", bool, False), _field(request, "debug", bool, False),
                      _field(request, "topics", bool, False))
        if self.status is None:
            raise RequestError("lab_status: this server has no ROS master to watch")
        parts = {part for part, _ in wants.parts()}
        for part in self.status_parts - parts:
            self.outbox.close_lane(self._status_lane(part))
        for part in parts - self.status_parts:
            self.outbox.open_lane(self._status_lane(part), 1)
        self.status_parts = parts
        if not parts:
            self.status.unwatch(self.client)
            return

        def deliver(part: str, text: str) -> None:
            if self.outbox.put(self._status_lane(part), text):
                self.wake()
        self.status.watch(self.client, wants, deliver)

    def _status_lane(self, part: str) -> Tuple[Hashable, str, str]:
        return (self.client, "lab_status", part)

    HANDLERS = {"advertise": _advertise, "unadvertise": _unadvertise, "publish": _publish,
                "subscribe": _subscribe, "unsubscribe": _unsubscribe, "call_service": _call_service,
                "lab_status": _lab_status}

    def close(self) -> None:
        """The client left: drop its subscriptions and publishers."""
        with self._lock:
            self.closed = True
            if self.status is not None and self.status_parts:
                self.status.unwatch(self.client)
            for key in list(self.subscriptions):
                self._drop_subscription(key)
            for topic in list(self.advertised):
                self.advertised.discard(topic)
                self.bridge.unadvertise(self.client, topic)
