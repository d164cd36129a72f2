"""lab_view against turtlesim, for what it loads (each costs resident memory in every student's
container, docs/lab_page.md): the page's traffic (the canvas's call_service, which names no type,
and its subscriptions) maps no Pillow into lab_view; a camera (a compressed /turtlesim/image) does,
and gets JPEG frames. A service's type is asked of the service's node, without rosservice, and is
what rosservice says."""
from __future__ import annotations

import asyncio
import json
import subprocess
import sys
import time

from course_web import frames

PILLOW_LIBRARY = "PIL/_imaging"  # Pillow's C module, mapped by its first import
TIMEOUT_S = 30.0
SERVICES = ("/turtlesim/canvas", "/spawn", "/clear", "/turtle1/teleport_absolute")


def lab_view_maps(lab) -> str:
    pid = lab.server.proc.pid
    with open("/proc/%d/cmdline" % pid, "rb") as cmdline:
        assert b"lab_view" in cmdline.read()
    with open("/proc/%d/maps" % pid) as maps:
        return maps.read()


def test_the_pages_traffic_loads_no_pillow_and_a_camera_does(lab, client_class):
    async def scenario():
        client = await client_class.connect(lab.ws_url())
        client.send(op="call_service", id="canvas", service="/turtlesim/canvas", args={})
        reply = await client.expect(lambda m: m.get("id") == "canvas", timeout=TIMEOUT_S, what="the canvas")
        assert reply["result"] is True and "turtles" in json.loads(reply["values"]["message"]), reply
        client.send(op="subscribe", id="pose", topic="/turtle1/pose")
        await client.expect(lambda m: m.get("topic") == "/turtle1/pose", timeout=TIMEOUT_S, what="a pose")
        assert PILLOW_LIBRARY not in lab_view_maps(lab)

        client.send(op="subscribe", id="camera", topic="/turtlesim/image", compression="jpeg")
        deadline = time.monotonic() + TIMEOUT_S
        while not client.images and time.monotonic() < deadline:
            await client.receive(0.5)
        assert client.images, "no picture of /turtlesim/image within %.0f s" % TIMEOUT_S
        header, body = frames.unpack(client.images[0])
        assert (header["op"], header["topic"], header["format"]) == ("image", "/turtlesim/image", "jpeg")
        assert body[:2] == b"\xff\xd8"
        assert PILLOW_LIBRARY in lab_view_maps(lab)
        client.close()
    asyncio.run(scenario())


ASK_TYPES = """
import json, sys
from course_web.protocol import RequestError
from course_web.ros_bridge import RosBridge
bridge = RosBridge()
ours = [bridge.service_type(name) for name in %r]
try:
    bridge.service_type("/no_such_service")
    missing = None
except RequestError as err:
    missing = str(err)
loaded = [name for name in ("rosservice", "rosmsg") if name in sys.modules]
import rosservice
print(json.dumps({"ours": ours, "missing": missing, "loaded": loaded,
                  "rosservice": [rosservice.get_service_type(name) for name in %r]}))
""" % (SERVICES, SERVICES)


def test_a_services_type_is_asked_of_its_node_without_rosservice(lab):
    done = subprocess.run([sys.executable, "-c", ASK_TYPES], env=lab.master.env, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr[-3000:]
    found = json.loads(done.stdout.strip().splitlines()[-1])
    assert found["ours"] == ["std_srvs/Trigger", "turtlesim/Spawn", "std_srvs/Empty", "turtlesim/TeleportAbsolute"]
    assert found["ours"] == found["rosservice"]
    assert found["missing"] == "unknown service /no_such_service"
    assert found["loaded"] == []
