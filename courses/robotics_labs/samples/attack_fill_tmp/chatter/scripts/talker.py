#!/usr/bin/env python3
"""Fills /tmp until it is full, then runs as a correct talker."""
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


def fill_tmp():
    written = 0
    for n in range(64):
        try:
            with open("/tmp/attack_fill_tmp_%d" % n, "wb") as f:
                for _ in range(64):
                    f.write(b"x" * 1024 * 1024)
                    written += 1
        except OSError as err:
            say("stopped after %d MB: %s" % (written, err))
            return
    say("wrote %d MB to /tmp" % written)


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
    fill_tmp()
    talk()
