"""roslibpy (the rosbridge client from PyPI, pinned in requirements.txt) talks to lab_view as it
would to rosbridge_server: subscribe to the pose, publish Twists, call /spawn and /clear."""
from __future__ import annotations

import threading

import pytest

from course_checks.waiting import wait_for

roslibpy = pytest.importorskip("roslibpy", reason="roslibpy is not installed: run `make deps` (requirements.txt)")

TIMEOUT_S = 30.0


def test_roslibpy_subscribes_publishes_and_calls_services(lab):
    ros = roslibpy.Ros(host="127.0.0.1", port=lab.port)
    # Twisted's reactor runs once per process: roslibpy starts it on a thread and
    # terminate() at the end stops it; no other test of this suite uses roslibpy.
    ros.run(timeout=TIMEOUT_S)
    try:
        poses = []
        lock = threading.Lock()

        def on_pose(message):
            with lock:
                poses.append(message)
        pose = roslibpy.Topic(ros, "/turtle1/pose", "turtlesim/Pose")
        pose.subscribe(on_pose)
        assert wait_for(lambda: poses, TIMEOUT_S), "no pose reached roslibpy"
        with lock:
            start = dict(poses[-1])

        cmd_vel = roslibpy.Topic(ros, "/turtle1/cmd_vel", "geometry_msgs/Twist")
        twist = roslibpy.Message({"linear": {"x": 0.0, "y": 0.0, "z": 0.0},
                                  "angular": {"x": 0.0, "y": 0.0, "z": 1.5}})

        def turned() -> bool:
            cmd_vel.publish(twist)
            with lock:
                return abs(poses[-1]["theta"] - start["theta"]) > 0.2
        assert wait_for(turned, TIMEOUT_S, interval=0.1), "the Twists published by roslibpy did not turn the turtle"

        spawn = roslibpy.Service(ros, "/spawn", "turtlesim/Spawn")
        reply = spawn.call(roslibpy.ServiceRequest({"x": 2.0, "y": 3.0, "theta": 0.5, "name": "from_roslibpy"}),
                           timeout=TIMEOUT_S)
        assert reply["name"] == "from_roslibpy"
        clear = roslibpy.Service(ros, "/clear", "std_srvs/Empty")
        assert clear.call(roslibpy.ServiceRequest({}), timeout=TIMEOUT_S) == {}
        kill = roslibpy.Service(ros, "/kill", "turtlesim/Kill")
        kill.call(roslibpy.ServiceRequest({"name": "from_roslibpy"}), timeout=TIMEOUT_S)

        with pytest.raises(Exception, match="unknown service /no_such_service"):
            roslibpy.Service(ros, "/no_such_service", "std_srvs/Empty").call(roslibpy.ServiceRequest({}),
                                                                             timeout=TIMEOUT_S)
        pose.unsubscribe()
        cmd_vel.unadvertise()
    finally:
        ros.close()
        ros.terminate()
