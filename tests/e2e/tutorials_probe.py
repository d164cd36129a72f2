#!/usr/bin/env python3
"""The probe of tests/e2e/test_tutorials.py: a node of the master a turtle_tf2 demo runs on
(course_testkit.tutorials.demo starts it). Once turtle2 has caught up from where the listener
spawned it, turtle1 drives an arc and stops; the samples of both poses and their distance go to
stdout as JSON ({"samples": [[phase, t, x1, y1, x2, y2, distance], ...]}, or {"error": why})."""
from __future__ import annotations

import json
import math
import sys
import time
from typing import Dict

import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from course_checks.waiting import wait_for
from course_testkit.tutorials import CAUGHT_UP_M, DRIVE_S, FOLLOW_S, SAMPLE_S, START_TIMEOUT_S


def probe() -> int:
    rospy.init_node("tutorials_check_probe", disable_signals=True)
    poses: Dict[str, Pose] = {}
    for name in ("turtle1", "turtle2"):
        rospy.Subscriber("/%s/pose" % name, Pose, lambda msg, n=name: poses.__setitem__(n, msg))
    drive = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
    if not wait_for(lambda: len(poses) == 2 and drive.get_num_connections(), START_TIMEOUT_S, 0.1):
        print(json.dumps({"error": "no pose from %s" % " and ".join(sorted({"turtle1", "turtle2"} - set(poses)))
                          or "turtlesim does not subscribe /turtle1/cmd_vel"}))
        return 1
    samples = []
    t0 = time.monotonic()

    def distance() -> float:
        return math.hypot(poses["turtle1"].x - poses["turtle2"].x, poses["turtle1"].y - poses["turtle2"].y)

    def sample(phase: str) -> None:
        one, two = poses["turtle1"], poses["turtle2"]
        samples.append([phase, round(time.monotonic() - t0, 2), round(one.x, 3), round(one.y, 3),
                        round(two.x, 3), round(two.y, 3), round(distance(), 3)])

    def record(phase: str, seconds: float, until=lambda: False, action=lambda: None) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end and not until():
            action()
            sample(phase)
            wait_for(lambda: time.monotonic() >= samples[-1][1] + t0 + SAMPLE_S, SAMPLE_S + 1, 0.02)

    record("catch-up", START_TIMEOUT_S, until=lambda: distance() < CAUGHT_UP_M)
    arc = Twist()
    arc.linear.x, arc.angular.z = 2.0, 1.0
    record("drive", DRIVE_S, action=lambda: drive.publish(arc))
    drive.publish(Twist())
    record("follow", FOLLOW_S)
    sample("end")
    print(json.dumps({"samples": samples}))
    rospy.signal_shutdown("measured")
    return 0


if __name__ == "__main__":
    sys.exit(probe())
