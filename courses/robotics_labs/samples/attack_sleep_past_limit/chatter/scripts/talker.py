#!/usr/bin/env python3
"""A correct talker that leaves a child behind: deaf to every signal it can ignore, in a new session, with an empty environment, sleeping 1000 s (past any time limit)."""
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


def leave_sleeper():
    if os.fork() == 0:
        os.setsid()
        import signal
        for s in signal.Signals:
            try:
                signal.signal(s, signal.SIG_IGN)
            except (OSError, ValueError, RuntimeError):
                pass
        os.execve("/bin/sleep", ["sleep", "1000"], {})


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
    leave_sleeper()
    talk()
