#!/usr/bin/env python3
"""An idle TCP connection beside a rospy node's TCPROS port (hidden robustness case T19), figures,
no assertions: with one connection open that sends nothing, the time a new subscriber takes to get
its first message and a service call to answer, ROUNDS times; on turtlesim (course_rospy.
inbound_headers installed) and, as the control, on `rostopic pub` (plain rospy), where the
subscriber gives up after LIMIT s.
Then half-sent headers (issue 40; course_testkit.half_headers) on turtlesim, gzserver and the relay:
the node's threads and open files before, with 50 open, and 1 s after they closed (and how soon
they were back); with 500 left open, the same, the node's CPU against its quiet CPU, and a new
subscriber's and a service call's times.
    python3 bench/idle_connection_bench.py [ROUNDS]      (default 10)"""
import socket
import statistics
import sys
import time

from course_testkit.benchmarks import private_master

LIMIT_S = 5.0


def timed(action) -> float:
    started = time.monotonic()
    try:
        action()
    except OSError:
        return float("inf")
    return time.monotonic() - started


def wait_address(tcpros, uri, node, topic):
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        try:
            return tcpros.topic_address(uri, node, topic)
        except (OSError, LookupError):
            time.sleep(0.1)
    raise SystemExit("%s did not come up" % node)


def show(what, times) -> None:
    done = [t for t in times if t != float("inf")]
    print("%-52s median %s, max %s, %d of %d within %.0f s" % (
        what, "%.1f ms" % (1000 * statistics.median(done)) if done else "-",
        "%.1f ms" % (1000 * max(done)) if done else "-", len(done), len(times), LIMIT_S), flush=True)


def load() -> str:
    with open("/proc/loadavg") as f:
        return "load average " + " ".join(f.read().split()[:3])


def half_header_figures(name: str, node) -> None:
    """What 50 half headers that close and 500 left open cost `node` (a NodeUnderTest)."""
    from course_testkit import half_headers as hh
    before = node.warmed_up()
    socks = hh.open_half_headers(node.address, 50)
    during = hh.process_use(node.pid)
    hh.close_all(socks)
    closed_at = time.monotonic()
    back = hh.back_within(node.pid, before, LIMIT_S)
    back_s = time.monotonic() - closed_at
    time.sleep(max(0.0, 1.0 - back_s))
    came_back = back.files <= before.files and back.threads <= before.threads
    print("%-9s 50 half headers that close: before %s; open %s; %s %.0f ms; 1 s after %s  (%s)" % (
        name, before, during, "back to before after" if came_back else "NOT back to before after",
        1000 * back_s, hh.process_use(node.pid), load()), flush=True)
    quiet = hh.cpu_share(node.pid)
    started = time.monotonic()
    socks = hh.open_half_headers(node.address, 500)
    opened_s = time.monotonic() - started
    try:
        right_after = hh.process_use(node.pid)
        settled = hh.settled_use(node.pid)
        busy = hh.cpu_share(node.pid)
        subscribe, call = timed(lambda: node.subscribe(LIMIT_S)), timed(lambda: node.call(LIMIT_S))
    finally:
        hh.close_all(socks)
    print("%-9s 500 half headers left open (in %.2f s): at once %s, settled %s; CPU %.3f s/s (quiet %.3f); "
          "subscriber %.1f ms, call %.1f ms  (%s)" % (name, opened_s, right_after, settled, busy, quiet,
                                                       1000 * subscribe, 1000 * call, load()), flush=True)


def half_headers_on_each_node(tcpros) -> None:
    from gazebo_msgs.srv import GetWorldProperties, GetWorldPropertiesRequest
    from roscpp.srv import GetLoggers, GetLoggersRequest
    from rosgraph_msgs.msg import Clock
    from std_msgs.msg import String
    from std_srvs.srv import Empty, EmptyRequest
    from turtlesim.msg import Pose
    from course_checks.nodes import find_executable
    from course_testkit.half_headers import NodeUnderTest
    with private_master() as ros:  # the nodes' own processes (not rosrun's shell), for /proc
        nodes = {"turtlesim": ros.start([find_executable("turtlesim", "turtlesim_node")], "turtlesim"),
                 "gazebo": ros.start([find_executable("mujoco_gazebo", "gzserver")], "gazebo"),
                 "relay": ros.start([find_executable("course_relay", "relay"), "/words", "__name:=relay"], "relay")}
        ros.start(["rostopic", "pub", "-r", "50", "/words", "std_msgs/String", "data: w", "__name:=words"], "words")
        wiring = {"turtlesim": ("/turtlesim", "/turtle1/pose", Pose, "/clear", Empty, EmptyRequest()),
                  "gazebo": ("/gazebo", "/clock", Clock, "/gazebo/get_world_properties", GetWorldProperties,
                             GetWorldPropertiesRequest()),
                  "relay": ("/relay", "/words_relay", String, "/relay/get_loggers", GetLoggers, GetLoggersRequest())}
        for name, (node, topic, msg, service, srv, request) in wiring.items():
            address = wait_address(tcpros, ros.uri, node, topic)
            server = tcpros.service_address(ros.uri, service)
            half_header_figures(name, NodeUnderTest(
                pid=nodes[name].proc.pid, address=address,
                subscribe=lambda t, a=address, topic=topic, msg=msg: tcpros.receive_one(a, topic, msg, t),
                call=lambda t, s=server, n=service, c=srv, r=request: tcpros.call(s, n, c, r, t)))


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    from course_testkit import tcpros
    from std_msgs.msg import String
    from turtlesim.msg import Pose
    from turtlesim.srv import Spawn, SpawnRequest
    with private_master() as ros:
        ros.start(["rosrun", "turtlesim", "turtlesim_node"], "turtlesim")
        ros.start(["rostopic", "pub", "-r", "10", "/control", "std_msgs/String", "data: x", "__name:=control"],
                  "control")
        sim = wait_address(tcpros, ros.uri, "/turtlesim", "/turtle1/pose")
        control = wait_address(tcpros, ros.uri, "/control", "/control")
        spawn = tcpros.service_address(ros.uri, "/spawn")
        subscribe, call, plain = [], [], []
        for n in range(rounds):
            with socket.create_connection(sim), socket.create_connection(control):
                subscribe.append(timed(lambda: tcpros.receive_one(sim, "/turtle1/pose", Pose, LIMIT_S)))
                call.append(timed(lambda: tcpros.call(spawn, "/spawn", Spawn, SpawnRequest(1 + n * 0.5, 2, 0, "t%d" % n),
                                                      LIMIT_S)))
                if n < 2:  # each blocked attempt costs LIMIT_S
                    plain.append(timed(lambda: tcpros.receive_one(control, "/control", String, LIMIT_S)))
        show("turtlesim, subscribe /turtle1/pose, first message", subscribe)
        show("turtlesim, call /spawn", call)
        show("rostopic pub (plain rospy), subscribe, first message", plain)
    half_headers_on_each_node(tcpros)


if __name__ == "__main__":
    main()
