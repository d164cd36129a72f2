#!/usr/bin/env python3
"""Probes run inside a network namespace by test_netns.py (a test in the root namespace cannot
reach the namespaces' addresses). Each prints one JSON line and exits 0 when its condition holds.

  netns_probe.py master UP_TIMEOUT            the master answers
  netns_probe.py registered NODE TIMEOUT      NODE is registered with the master
  netns_probe.py moves TIMEOUT [METRES]       /turtle1/pose moves at least METRES (default 0.5) within TIMEOUT s
  netns_probe.py still TIMEOUT                /turtle1/pose reports zero speed (the turtle stopped)
"""
import json
import math
import sys
import time

import rosgraph


def wait(condition, timeout_s, period_s=0.2):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        result = condition()
        if result:
            return result
        time.sleep(period_s)
    return condition()


def master_up():
    try:
        rosgraph.Master("/netns_probe").getPid()
        return True
    except Exception:
        return False


def node_names():
    try:
        pubs, subs, srvs = rosgraph.Master("/netns_probe").getSystemState()
    except Exception:
        return set()
    return {n for _, nodes in pubs + subs + srvs for n in nodes}


def main(argv):
    what, timeout_s = argv[0], float(argv[-1] if argv[0] != "moves" else argv[1])
    if what == "master":
        ok = bool(wait(master_up, timeout_s))
        print(json.dumps({"master": ok}))
        return 0 if ok else 1
    if what == "registered":
        ok = bool(wait(lambda: argv[1] in node_names(), timeout_s))
        print(json.dumps({"registered": argv[1], "ok": ok}))
        return 0 if ok else 1
    import rospy
    from turtlesim.msg import Pose
    rospy.init_node("netns_probe", anonymous=True, disable_signals=True)
    first = rospy.wait_for_message("/turtle1/pose", Pose, timeout=20.0)
    if what == "still":
        ok = bool(wait(lambda: rospy.wait_for_message("/turtle1/pose", Pose, timeout=5.0).linear_velocity == 0.0,
                       timeout_s))
        print(json.dumps({"still": ok}))
        return 0 if ok else 1
    metres = float(argv[2]) if len(argv) > 2 else 0.5

    def moved():
        pose = rospy.wait_for_message("/turtle1/pose", Pose, timeout=5.0)
        return math.hypot(pose.x - first.x, pose.y - first.y) >= metres and pose
    last = wait(moved, timeout_s)
    pose = rospy.wait_for_message("/turtle1/pose", Pose, timeout=5.0)
    print(json.dumps({"moved": bool(last), "start": [first.x, first.y], "end": [pose.x, pose.y]}))
    return 0 if last else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
