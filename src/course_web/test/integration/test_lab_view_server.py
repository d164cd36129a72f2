"""lab_view against turtlesim: the rosbridge ops work, bad requests get errors to their sender
only, 20 viewers are served fairly while one stalls, a latched message reaches a late client,
the page's JSON questions (/api/...) answer or say why, the page's own lab_status op tells the
client that asks and no other, and the token guards a wider address."""
from __future__ import annotations

import asyncio
import json
import re
import time
import urllib.error
import urllib.parse
import urllib.request

from course_checks.isolation import free_port
from course_testkit.master import system_state
from course_checks.nodes import find_executable
from course_checks.waiting import wait_for

VIEWERS = 20
WATCH_S = 4.0
TIMEOUT_S = 30.0
MAX_GROWTH_MB = 80


def is_pose(message):
    return message.get("op") == "publish" and message.get("topic") == "/turtle1/pose"


def resident_mb(pid):
    with open("/proc/%d/status" % pid) as status:
        kb = next(int(line.split()[1]) for line in status if line.startswith("VmRSS:"))
    return kb / 1024.0


def lab_view_subscribes(lab, topic):
    subscribers = dict(system_state(lab.master.uri)[1])
    return "/lab_view" in subscribers.get(topic, [])


def test_the_page_and_its_scripts_are_served(lab):
    for path in ("/", "/js/main.js", "/js/bridge.js", "/lab.css"):
        assert lab.status(path) == 200, path
    assert lab.status("/js/missing.js") == 404


def test_subscribe_publish_and_call_service_work_end_to_end(lab, client_class):
    async def scenario():
        client = await client_class.connect(lab.ws_url())
        client.send(op="call_service", id="tp", service="/turtle1/teleport_absolute",
                    args={"x": 3.0, "y": 3.0, "theta": 0.0})
        reply = await client.expect(lambda m: m.get("id") == "tp", what="the teleport's reply")
        assert reply == {"op": "service_response", "id": "tp", "service": "/turtle1/teleport_absolute",
                         "result": True, "values": {}}
        client.send(op="subscribe", id="pose", topic="/turtle1/pose", type="turtlesim/Pose")
        start = await client.expect(lambda m: is_pose(m) and abs(m["msg"]["x"] - 3.0) < 0.01, what="the pose at x=3")
        client.send(op="advertise", topic="/turtle1/cmd_vel", type="geometry_msgs/Twist")
        deadline = time.monotonic() + TIMEOUT_S
        moved = None
        while moved is None and time.monotonic() < deadline:
            client.send(op="publish", topic="/turtle1/cmd_vel", msg={"linear": {"x": 1.0}})
            message = await client.receive(0.5)
            if message is not None and is_pose(message) and message["msg"]["x"] > start["msg"]["x"] + 0.1:
                moved = message
        assert moved is not None, "the turtle did not move on the Twists published through the bridge"
        client.send(op="unsubscribe", id="pose", topic="/turtle1/pose")
        client.send(op="call_service", id="after", service="/clear")
        await client.expect(lambda m: m.get("id") == "after", what="the /clear reply")
        # After the unsubscribe is processed (requests are handled in order), no pose follows.
        assert not any(is_pose(m) for m in [await client.receive(0.5)] if m)
        client.close()
    asyncio.run(scenario())


BAD_REQUESTS = [
    ('{"op": "subscribe", "topic": ', "malformed JSON"),
    ('{"op": "launch_rocket"}', "unknown op 'launch_rocket'"),
    ('{"op": "subscribe", "id": "x", "topic": "/no_such_topic"}', "unknown topic /no_such_topic"),
    ('{"op": "advertise", "topic": "/web_test", "type": "no_pkg/NoType"}', "unknown message type 'no_pkg/NoType'"),
    ('{"op": "advertise", "topic": "/turtle1/pose", "type": "geometry_msgs/Twist"}',
     "type mismatch: /turtle1/pose has type turtlesim/Pose, not geometry_msgs/Twist"),
    ('{"op": "subscribe", "topic": "/turtle1/pose", "type": "std_msgs/String"}', "type mismatch"),
    ('{"op": "publish", "topic": "/turtle1/cmd_vel", "msg": {"linear": {"x": "fast"}}}',
     "linear.x: expected a number (float64), got a string"),
    ('{"op": "subscribe", "topic": "/turtle1/pose", "compression": "jpeg"}', "compression jpeg is for sensor_msgs/Image"),
    ('{"op": "call_service", "service": "/no_such_service"}', "unknown service /no_such_service"),
    ('{"op": "call_service", "service": "/spawn", "args": {"x": "left"}}', "x: expected a number"),
]


def test_bad_requests_get_clear_errors_only_to_their_sender_and_the_server_stays_up(lab, client_class, error_check):
    async def scenario():
        bad = await client_class.connect(lab.ws_url())
        bystander = await client_class.connect(lab.ws_url())
        bystander.send(op="subscribe", topic="/turtle1/pose")
        await bystander.expect(is_pose, what="a pose for the bystander")
        for frame, complaint in BAD_REQUESTS + [('{"op": "publish", "topic": "/x", "pad": "%s"}'
                                                 % ("x" * lab.message_limit), "the limit is %d bytes" % lab.message_limit)]:
            bad.send_raw(frame)
            error = await bad.expect(error_check, what="an error for %s" % frame[:60])
            assert complaint in error["msg"], (frame[:80], error)
        # The bystander saw poses all along and never an error; the bad client still works.
        seen = [await bystander.receive(1.0) for _ in range(20)]
        assert all(m is not None and is_pose(m) for m in seen), seen
        bad.send(op="call_service", id="ok", service="/turtle1/teleport_relative", args={"linear": 0.0, "angular": 0.1})
        assert (await bad.expect(lambda m: m.get("id") == "ok"))["result"] is True
        assert lab.server.running()
        bad.close()
        bystander.close()
    asyncio.run(scenario())


def test_twenty_viewers_are_served_fairly_while_one_stalls(lab, client_class):
    async def scenario():
        # The stalled viewer asks for every canvas frame as JSON (~1 MB each) and never reads
        # (tornado's client stops reading the socket while its one-message queue is full): the
        # server must drop its frames, not queue them, and not make anyone else wait.
        stalled_client = await client_class.connect(lab.ws_url())
        stalled_client.send(op="subscribe", topic="/turtlesim/image", type="sensor_msgs/Image")
        rss_before = resident_mb(lab.server.proc.pid)
        viewers = [await client_class.connect(lab.ws_url()) for _ in range(VIEWERS)]
        for viewer in viewers:
            viewer.send(op="subscribe", topic="/turtle1/pose")
        await asyncio.gather(*(viewer.expect(is_pose, what="a first pose") for viewer in viewers))
        counts = [0] * VIEWERS

        async def watch(index, viewer):
            deadline = time.monotonic() + WATCH_S
            while time.monotonic() < deadline:
                message = await viewer.receive(deadline - time.monotonic())
                if message is not None and is_pose(message):
                    counts[index] += 1
        await asyncio.gather(*(watch(i, v) for i, v in enumerate(viewers)))
        # turtlesim publishes 62.5 poses a second; on a loaded 2-core machine each viewer must
        # still see a steady stream, and none far less than the best served.
        assert min(counts) >= 5 * WATCH_S, counts
        assert min(counts) >= 0.5 * max(counts), counts
        late = await client_class.connect(lab.ws_url())
        late.send(op="call_service", id="late", service="/turtle1/teleport_relative", args=[0.0, 0.0])
        assert (await late.expect(lambda m: m.get("id") == "late", timeout=30.0))["result"] is True
        # ~30 JSON frames of ~1 MB a second for the stalled viewer: queued, they would be
        # hundreds of MB by now; dropped (its lane keeps 10), lab_view stays near its size.
        growth = resident_mb(lab.server.proc.pid) - rss_before
        print("lab_view grew by %.0f MB while a viewer stalled" % growth)
        assert growth < MAX_GROWTH_MB, growth
        assert lab_view_subscribes(lab, "/turtle1/pose") and lab_view_subscribes(lab, "/turtlesim/image")
        for client in viewers + [late, stalled_client]:
            client.close()
        # When the viewers have gone, lab_view lets go of the topics (no leaked subscriber).
        assert wait_for(lambda: not lab_view_subscribes(lab, "/turtle1/pose")
                        and not lab_view_subscribes(lab, "/turtlesim/image"), TIMEOUT_S)
        return counts
    counts = asyncio.run(scenario())
    print("poses per viewer in %.0f s: %s" % (WATCH_S, counts))


def test_a_wider_address_requires_the_token(lab, client_class):
    port = free_port()
    # A node name of its own: a second /lab_view would make the master shut the lab's one down.
    server = lab.start_server(port, "--address", "0.0.0.0", "__name:=lab_view_guarded")
    try:
        token = re.search(r"\?token=([A-Za-z0-9_-]+)", server.output()).group(1)
        assert lab.status("/", port) == 403
        assert lab.status("/js/main.js", port) == 403
        assert lab.status("/?token=wrong", port) == 403
        assert lab.status("/?token=%s" % token, port) == 200
        assert lab.status("/js/main.js", port, Cookie="course_web_token=%s" % token) == 200
        assert lab.status("/api/topics", port) == 403
        assert lab.status("/api/topics?token=%s" % token, port) == 200

        async def scenario():
            refused = await client_class.connect(lab.ws_url(port))
            assert await refused.receive(20.0) is None
            assert refused.connection.close_code == 1008
            assert "token" in refused.connection.close_reason
            allowed = await client_class.connect(lab.ws_url(port, token))
            allowed.send(op="subscribe", topic="/turtle1/pose")
            await allowed.expect(is_pose, what="a pose through the token-guarded server")
            allowed.close()
        asyncio.run(scenario())
    finally:
        lab.master.stop_node(server)


def api(lab, question, **params):
    """(status, answer) of GET /api/<question>?params."""
    url = lab.url("/api/%s%s" % (question, "?" + urllib.parse.urlencode(params) if params else ""))
    try:
        with urllib.request.urlopen(url, timeout=TIMEOUT_S) as reply:
            return reply.status, json.loads(reply.read())
    except urllib.error.HTTPError as err:
        return err.code, json.loads(err.read() or b"{}")


def test_the_api_answers_the_pages_questions(lab):
    status, answer = api(lab, "topics")
    assert status == 200 and {"name": "/turtle1/pose", "type": "turtlesim/Pose"} in answer["topics"]
    status, answer = api(lab, "graph")
    assert status == 200 and "/turtlesim" in answer["nodes"], answer
    assert {"from": "/turtlesim", "to": "/turtle1/pose"} in answer["edges"]
    status, answer = api(lab, "plot", path="/turtle1/pose/x:theta")
    assert status == 200 and [f["label"] for f in answer["fields"]] == ["/turtle1/pose/x", "/turtle1/pose/theta"]


def test_lab_status_tells_what_a_client_asks_and_nothing_to_others(lab, client_class, error_check):
    def is_status(message):
        return message.get("op") == "lab_status"

    async def scenario():
        page = await client_class.connect(lab.ws_url())
        other = await client_class.connect(lab.ws_url())  # a rosbridge client: never asks
        other.send(op="subscribe", topic="/turtle1/pose")
        page.send(op="lab_status", health="/turtlesim/scene", graph=True, topics=True)
        told = {}
        while len(told) < 3:
            message = await page.expect(is_status, what="the lab's status")
            told.update((part, answer) for part, answer in message.items() if part != "op")
        assert told["health"]["state"] == "ok" and told["health"]["publishers"] == ["/turtlesim"], told["health"]
        assert {"from": "/turtlesim", "to": "/turtle1/pose"} in told["graph"]["edges"]
        assert {"name": "/turtle1/pose", "type": "turtlesim/Pose"} in told["topics"]["topics"]
        page.send(op="lab_status", id="bad", graph="yes")
        assert '"graph" must be true or false' in (await page.expect(error_check))["msg"]
        page.send(op="lab_status")  # nothing more
        seen = [await other.receive(0.2) for _ in range(20)]
        assert seen and not any(m and is_status(m) for m in seen)
        page.close()
        other.close()
    asyncio.run(scenario())
    status, answer = api(lab, "health", topic="/turtlesim/scene")
    assert status == 200 and answer["state"] == "ok", answer
    status, answer = api(lab, "health", topic="/nobody/scene")
    assert status == 200 and answer["state"] == "no-publisher", answer


def test_bad_api_questions_say_why_and_the_server_stays_up(lab):
    for params, said in (({}, "give a field"), ({"path": "/turtle1/pose/nope"}, "has no field nope"),
                         ({"path": "/nowhere/x"}, "does not exist"), ({"path": "\x00\u00ff" * 3}, ""),
                         ({"path": "/turtle1/pose/x" * 500}, "too long"), ({"path": "/a/b[99999999999999999999]"}, "")):
        status, answer = api(lab, "plot", **params)
        assert status == 400 and said in answer["error"], (params, status, answer)
    assert lab.status("/api/unknown") == 404
    assert api(lab, "topics")[0] == 200


def test_a_latched_message_reaches_a_client_that_joins_a_shared_feed_late(lab, client_class):
    latched = lab.master.start([find_executable("tf2_ros", "static_transform_publisher"),
                                "0", "0", "1", "0", "0", "0", "world", "late_frame"], "latched_tf")

    def is_static(message):
        return message.get("topic") == "/tf_static" and any(
            t["child_frame_id"] == "late_frame" for t in message["msg"]["transforms"])

    async def scenario():
        first = await client_class.connect(lab.ws_url())
        first.send(op="subscribe", topic="/tf_static", type="tf2_msgs/TFMessage")
        await first.expect(is_static, timeout=TIMEOUT_S, what="the static transform (first client)")
        second = await client_class.connect(lab.ws_url())  # the feed exists: rospy will not resend
        second.send(op="subscribe", topic="/tf_static", type="tf2_msgs/TFMessage")
        await second.expect(is_static, timeout=TIMEOUT_S, what="the static transform (late client)")
        first.close()
        second.close()
    try:
        asyncio.run(scenario())
    finally:
        lab.master.stop_node(latched)
