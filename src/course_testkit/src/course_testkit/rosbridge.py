"""Drive turtlesim through a rosbridge v2 websocket, as the lab page's teleop panel does, and count
the canvas frames it receives, as the page's canvas panel subscribes to them (the page's own
server, or the page behind a proxy). Needs tornado alone (Debian's python3-tornado),
no rospy: the podman suites (tests/e2e/test_image.py) run it with Debian's python3 outside the workspace."""
from __future__ import annotations

import asyncio
import json
import time
from typing import Tuple

import tornado.websocket

TIMEOUT_S = 20.0
TWISTS = 20  # a Twist every 0.1 s for 2 s: the teleop's key repeat


def drive_turtle(ws_url: str, speed: float = 2.0) -> Tuple[float, float]:
    """turtle1's x before, and after 2 s of forward Twists published through the websocket at
    `ws_url` (ws://...; its query may carry the page's token)."""
    async def drive() -> Tuple[float, float]:
        socket = await tornado.websocket.websocket_connect(ws_url, connect_timeout=TIMEOUT_S)
        send = lambda message: socket.write_message(json.dumps(message))  # noqa: E731
        await send({"op": "subscribe", "topic": "/turtle1/pose", "type": "turtlesim/Pose"})
        await send({"op": "advertise", "topic": "/turtle1/cmd_vel", "type": "geometry_msgs/Twist"})

        async def pose_x() -> float:
            while True:
                text = await asyncio.wait_for(socket.read_message(), TIMEOUT_S)
                if text is None:
                    raise ConnectionError("the websocket at %s closed" % ws_url.split("?")[0])
                message = json.loads(text)
                if message.get("topic") == "/turtle1/pose":
                    return float(message["msg"]["x"])
        before = await pose_x()
        twist = {"linear": {"x": speed, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}}
        for _ in range(TWISTS):
            await send({"op": "publish", "topic": "/turtle1/cmd_vel", "msg": twist})
            await asyncio.sleep(0.1)
        after, until = before, time.monotonic() + 2.0
        while time.monotonic() < until:  # the poses queued while publishing, then fresh ones
            after = await pose_x()
        socket.close()
        return before, after
    return asyncio.run(drive())


def frame_rate(ws_url: str, seconds: float, topic: str = "/turtlesim/image") -> float:
    """Image frames per second that arrive through the websocket at `ws_url`, subscribed to as the
    page's canvas panel subscribes (JPEG binary frames, queue_length 1), counted for `seconds`
    from the first frame."""
    async def count() -> float:
        socket = await tornado.websocket.websocket_connect(ws_url, connect_timeout=TIMEOUT_S,
                                                          max_message_size=1 << 26)
        await socket.write_message(json.dumps({"op": "subscribe", "id": "frames", "topic": topic,
                                               "type": "sensor_msgs/Image", "compression": "jpeg",
                                               "queue_length": 1}))
        frames, began, until = 0, None, None
        while until is None or time.monotonic() < until:
            left = TIMEOUT_S if until is None else until - time.monotonic()
            try:
                message = await asyncio.wait_for(socket.read_message(), max(left, 0.001))
            except asyncio.TimeoutError:
                if until is None:
                    raise ConnectionError("no frame of %s through %s within %.0f s" % (topic, ws_url.split("?")[0],
                                                                                        TIMEOUT_S))
                break
            if message is None:
                raise ConnectionError("the websocket at %s closed" % ws_url.split("?")[0])
            if not isinstance(message, bytes):
                continue
            if began is None:  # the clock starts at the first frame
                began = time.monotonic()
                until = began + seconds
            else:
                frames += 1
        socket.close()
        return frames / (time.monotonic() - began)
    return asyncio.run(count())
