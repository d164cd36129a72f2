#!/usr/bin/env python3
"""An idle TCP connection beside a rospy node's TCPROS port (hidden robustness case T19), figures,
no assertions: with one connection open that sends nothing, the time a new subscriber takes to get
its first message and a service call to answer, ROUNDS times; on turtlesim (course_rospy.
inbound_threads installed) and, as the control, on `rostopic pub` (plain rospy), where the
subscriber gives up after LIMIT s.
    python3 bench/idle_connection_bench.py [ROUNDS]      (default 10)"""
import socket
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rosenv import private_master  # noqa: E402

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


if __name__ == "__main__":
    main()
