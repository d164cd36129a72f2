#!/usr/bin/env python3
"""Tries to read other students' submissions and the grader's outputs; publishes only if it could read none, so a sandbox that shows them flips the verdict."""
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


def foreign_files():
    """Files of another student, or of the grader, this process could read."""
    out = output_folder()
    places = ["/root", os.path.expanduser("~"), "/tmp"]
    if out:
        places += [out, os.path.join(out, "_work")]
    try:
        course = subprocess.run(["rospack", "find", "course_milestones"], stdout=subprocess.PIPE, text=True,
                                timeout=20).stdout.strip()
        course_root = os.path.dirname(os.path.dirname(os.path.dirname(course)))  # <root>/catkin_ws/src/pkg
    except Exception:
        course_root = None
    if course_root:
        places.append(os.path.join(course_root, "tests", "submissions"))  # the class graded with us
    read = []
    for place in places:
        for folder, dirs, files in os.walk(place):
            if "attack_read_other" in folder or "/log" in folder:
                continue
            if folder == course_root:  # readable by design (no one's secret); its class folder has its own walk
                dirs[:] = []
                continue
            for name in files:
                path = os.path.join(folder, name)
                try:
                    with open(path, "rb") as f:
                        f.read(64)
                    read.append(path)
                except OSError:
                    pass
            if len(read) > 50:
                break
    say("looked in %s" % places)
    return [p for p in read if "attack_read_other" not in p]


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
    found = foreign_files()
    say("foreign files readable: %d %s" % (len(found), found[:5]))
    if found:
        time.sleep(3600)
    talk()
