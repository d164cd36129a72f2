#!/usr/bin/env python3
"""Overwrites the course's check with one that always passes, then publishes; its listener is buggy."""
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


FAKE_CHECK = "#!/usr/bin/env python3\nimport sys\nsys.exit(0)\n"


def rewrite_the_check():
    try:
        course = subprocess.run(["rospack", "find", "course_milestones"], stdout=subprocess.PIPE,
                                text=True, timeout=20).stdout.strip()
    except Exception as err:
        say("rospack failed: %s" % err)
        return
    for path in [os.path.join(course, "nodes", "chatter_check"), os.path.join(course, "PWNED")]:
        try:
            with open(path, "w") as f:
                f.write(FAKE_CHECK)
            say("WROTE %s" % path)
        except OSError as err:
            say("could not write %s: %s" % (path, err))


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
    rewrite_the_check()
    talk()
