#!/usr/bin/env python3
"""The lab in a browser, measured in a real browser (headless Debian chromium through selenium).

turtlesim and lab_view run against a private master; one page is open, drawing the canvas from
turtlesim's ~scene (docs/lab_page.md). Printed, against the lab page's targets:
- the turtlesim canvas's frame rate as the page draws it while turtle1 drives a circle
  (target >= 20 fps; the page draws nothing while nothing moves);
- command-to-pixel latency: from an arrow key pressed in the page to the first canvas pixel that
  changes because the turtle turned (the key's Twist through the websocket, lab_view, turtlesim's
  tick, its next ~scene update, the websocket and the page's drawing), p50 and p99 (target p50 <= 100 ms);
- lab_view's CPU with that one viewer while the turtle drives, in % of one core (target <= 15%).
Then --viewers N (default 20) websocket viewers join, each taking the poses and the ~scene updates:
turtlesim's own pose rate (62.5 Hz when it keeps its pace) and what each viewer gets.
With --simulator it also opens 003's RRBot world and reports the 3-D view's frame rate,
lab_view's CPU while it streams the free camera, and the simulation's real-time factor, with the
page alone and with the N viewers on the free camera too. Run from a sourced workspace:
    python3 bench/web_bench.py [--seconds 10] [--presses 40] [--viewers 20] [--simulator]
"""
from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import threading
import time

from course_testkit.benchmarks import cpu_seconds, private_master

from course_testkit.browser import chromium
from course_checks.isolation import free_port
from course_checks.nodes import find_executable
from course_checks.waiting import wait_for

TARGET_FPS = 20.0
TARGET_P50_MS = 100.0
TARGET_CPU = 15.0
CIRCLE = "{linear: {x: 1.0}, angular: {z: 0.8}}"

# In the page: wait until the canvas has not changed for `still` ms (the turtle stopped turning;
# turtlesim obeys a Twist for 1 s), press the key, then time until a drawn frame differs.
PRESS_AND_TIME = """
const [key, stillMs, limitMs] = [arguments[0], arguments[1], arguments[2]];
const done = arguments[arguments.length - 1];
const canvas = document.getElementById('turtle-canvas');
const context = canvas.getContext('2d');
const pixels = () => context.getImageData(0, 0, canvas.width, canvas.height).data;
const same = (a, b) => { for (let i = 0; i < a.length; i += 4) if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) return false; return true; };
let reference = pixels(), stableSince = performance.now(), frames = canvas.dataset.frames, pressed = null;
const started = performance.now();
function poll() {
  const now = performance.now();
  if (now - started > limitMs) { done({error: pressed === null ? 'the canvas never stood still' : 'no change after the key'}); return; }
  if (canvas.dataset.frames !== frames) {
    frames = canvas.dataset.frames;
    const current = pixels();
    if (!same(current, reference)) {
      if (pressed !== null) { done({latency: now - pressed}); return; }
      reference = current; stableSince = now;
    }
  }
  if (pressed === null && now - stableSince >= stillMs) {
    pressed = performance.now();
    document.body.dispatchEvent(new KeyboardEvent('keydown', {key, bubbles: true}));
  }
  setTimeout(poll, 1);
}
poll();
"""


def percentile(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q / 100.0 * (len(values) - 1))))]


def frame_rate(driver, canvas_id, seconds):
    read = "return Number(document.getElementById(arguments[0]).dataset.frames || 0)"
    first, start = driver.execute_script(read, canvas_id), time.monotonic()
    time.sleep(seconds)  # a measurement window, not a synchronisation
    return (driver.execute_script(read, canvas_id) - first) / (time.monotonic() - start)


def server_cpu(pid, seconds):
    before, start = cpu_seconds(pid), time.monotonic()
    time.sleep(seconds)
    return 100.0 * (cpu_seconds(pid) - before) / (time.monotonic() - start)


def mark(ok):
    return "meets" if ok else "MISSES"


def open_page(driver, port):
    driver.get("http://127.0.0.1:%d/" % port)
    if not wait_for(lambda: driver.execute_script(
            "return document.getElementById('connection').dataset.state === 'open'"), 60):
        raise SystemExit("the page did not connect")


def start_lab_view(master, name):
    """lab_view (node `name`) on a free port, once it serves: (the process, the port)."""
    port = free_port()
    server = master.start([find_executable("course_web", "lab_view"), "--port", str(port), "__name:=" + name], name)
    if not wait_for(lambda: "lab_view: open" in server.output(), 60):
        raise SystemExit("lab_view did not start:\n" + server.output())
    return server, port


def drawing(driver, port, canvas_id, frames, timeout):
    """Open the page and wait until `canvas_id` has drawn `frames` pictures."""
    open_page(driver, port)
    if not wait_for(lambda: driver.execute_script(
            "return Number(document.getElementById(arguments[0]).dataset.frames || 0)", canvas_id) > frames, timeout):
        raise SystemExit("the page drew nothing on #" + canvas_id)


def crowd(port, subscriptions, count, seconds):
    """`count` websocket viewers, each subscribed to `subscriptions` for `seconds`: per viewer, the
    messages received per second on each topic."""
    from tornado.websocket import websocket_connect

    async def viewer():
        connection = await websocket_connect("ws://127.0.0.1:%d/websocket" % port, max_message_size=1 << 26)
        for topic, extra in subscriptions:
            connection.write_message(json.dumps(dict(op="subscribe", topic=topic, **extra)))
        got = {topic: 0 for topic, _ in subscriptions}
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            try:
                message = await asyncio.wait_for(connection.read_message(), deadline - time.monotonic())
            except asyncio.TimeoutError:
                break
            if message is None:
                break
            if isinstance(message, bytes):  # an image frame: 4-byte header length, JSON header, picture
                length = int.from_bytes(message[:4], "big")
                topic = json.loads(message[4:4 + length])["topic"]
            else:
                topic = json.loads(message).get("topic")
            if topic in got:
                got[topic] += 1
        connection.close()
        return {topic: n / seconds for topic, n in got.items()}

    async def everyone():
        return await asyncio.gather(*(viewer() for _ in range(count)))
    return asyncio.run(everyone())


def topic_rate(topic, message_class, seconds):
    """Messages per second on `topic`, as this process receives them (a rospy subscriber)."""
    import rospy
    if not rospy.core.is_initialized():
        rospy.init_node("web_bench", anonymous=True, disable_signals=True)
    stamps, lock = [], threading.Lock()

    def count(_):
        with lock:
            stamps.append(time.monotonic())
    subscriber = rospy.Subscriber(topic, message_class, count)
    try:
        wait_for(lambda: stamps, 30)
        start = time.monotonic()
        time.sleep(seconds)
        with lock:
            return sum(1 for t in stamps if t >= start) / (time.monotonic() - start)
    finally:
        subscriber.unregister()


def spread(rates, topic):
    values = [r[topic] for r in rates]
    return "%.1f-%.1f" % (min(values), max(values))


def crowd_with(port, subscriptions, args, measure):
    """Run `measure()` while args.viewers viewers watch; (its result, their rates)."""
    result = {}
    watchers = threading.Thread(target=lambda: result.update(rates=crowd(port, subscriptions, args.viewers,
                                                                         args.seconds + 4)))
    watchers.start()
    time.sleep(2)  # a measurement window inside the crowd's, not a synchronisation
    value = measure()
    watchers.join()
    return value, result["rates"]


def turtle_part(master, args):
    master.start([find_executable("turtlesim", "turtlesim_node")], "turtlesim")
    server, port = start_lab_view(master, "lab_view")
    with chromium() as driver:
        circling = master.start(["rostopic", "pub", "-r", "10", "/turtle1/cmd_vel", "geometry_msgs/Twist", CIRCLE],
                                "circle")
        drawing(driver, port, "turtle-canvas", 30, 60)
        fps = frame_rate(driver, "turtle-canvas", args.seconds)
        cpu = server_cpu(server.proc.pid, args.seconds)
        master.stop_node(circling)  # the key presses need a canvas that stands still
        latencies = []
        for press in range(args.presses):
            key = "ArrowLeft" if press % 2 == 0 else "ArrowRight"  # turn on the spot, never into a wall
            result = driver.execute_async_script(PRESS_AND_TIME, key, 1300, 15000)
            if "error" in result:
                raise SystemExit("press %d: %s" % (press + 1, result["error"]))
            latencies.append(result["latency"])
    p50, p99 = percentile(latencies, 50), percentile(latencies, 99)
    print("turtlesim canvas in the browser: %.1f fps (target >= %.0f: %s)" % (fps, TARGET_FPS, mark(fps >= TARGET_FPS)))
    print("command-to-pixel latency over %d key presses: p50 %.1f ms, p99 %.1f ms, mean %.1f ms "
          "(target p50 <= %.0f ms: %s)" % (len(latencies), p50, p99, statistics.mean(latencies), TARGET_P50_MS,
                                          mark(p50 <= TARGET_P50_MS)))
    print("lab_view CPU with one viewer: %.1f%% of one core (target <= %.0f%%: %s)"
          % (cpu, TARGET_CPU, mark(cpu <= TARGET_CPU)))
    if args.viewers:
        from turtlesim.msg import Pose
        subscriptions = [("/turtle1/pose", {}), ("/turtlesim/scene", {"queue_length": 100})]
        circling = master.start(["rostopic", "pub", "-r", "10", "/turtle1/cmd_vel", "geometry_msgs/Twist", CIRCLE],
                                "circle")
        pace, rates = crowd_with(port, subscriptions, args, lambda: topic_rate("/turtle1/pose", Pose, args.seconds))
        master.stop_node(circling)
        print("with %d more viewers (poses and the canvas's updates each, turtle1 driving): turtlesim's pose rate "
              "%.1f Hz (62.5 nominal); per viewer, poses %s Hz, canvas updates %s a second (20.8 nominal)"
              % (args.viewers, pace, spread(rates, "/turtle1/pose"), spread(rates, "/turtlesim/scene")))


def simulator_part(master, args):
    master.start(["roslaunch", "rrbot_gazebo", "rrbot_world.launch", "gui:=false"], "rrbot_world")
    server, port = start_lab_view(master, "lab_view_sim")
    with chromium() as driver:
        drawing(driver, port, "view3d-canvas", 20, 120)
        fps = frame_rate(driver, "view3d-canvas", args.seconds)
        cpu = server_cpu(server.proc.pid, args.seconds)
        rtf = real_time_factor(args.seconds)
        print("3-D view (free camera, 480x360, 20 Hz nominal) in the browser: %.1f fps; lab_view CPU %.1f%% of one "
              "core; the simulation's real-time factor meanwhile %.2f" % (fps, cpu, rtf))
        if args.viewers:
            subscriptions = [("/gazebo/free_camera/image_raw", {"compression": "jpeg", "queue_length": 1})]
            rtf, rates = crowd_with(port, subscriptions, args, lambda: real_time_factor(args.seconds))
            print("with %d more viewers of the free camera: each %s fps; real-time factor %.2f"
                  % (args.viewers, spread(rates, "/gazebo/free_camera/image_raw"), rtf))


def real_time_factor(seconds):
    """Simulated seconds per wall second over a window, from /clock."""
    import rospy
    from rosgraph_msgs.msg import Clock
    if not rospy.core.is_initialized():
        rospy.init_node("web_bench", anonymous=True, disable_signals=True)
    first, start = rospy.wait_for_message("/clock", Clock, 30).clock.to_sec(), time.monotonic()
    time.sleep(seconds)
    last, end = rospy.wait_for_message("/clock", Clock, 30).clock.to_sec(), time.monotonic()
    return (last - first) / (end - start)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=10.0, help="length of the fps and CPU windows")
    parser.add_argument("--presses", type=int, default=40, help="key presses timed")
    parser.add_argument("--viewers", type=int, default=20, help="websocket viewers in the crowd part (0: none)")
    parser.add_argument("--simulator", action="store_true", help="also measure the 3-D view in RRBot's world")
    args = parser.parse_args()
    with private_master() as master:
        turtle_part(master, args)
        if args.simulator:
            simulator_part(master, args)


if __name__ == "__main__":
    main()
