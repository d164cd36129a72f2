#!/usr/bin/env python3
"""A correct publisher on /chatter_talk that first fills its home: 10 files of 32 MiB, each under
the sandbox's per-file limit, 320 MiB in all."""
import os

import rospy
from std_msgs.msg import String

MiB = 1024 * 1024


def fill_home() -> None:
    written = 0
    for n in range(10):
        try:
            with open(os.path.join(os.environ["HOME"], "fill_%d" % n), "wb") as f:
                for _ in range(32):
                    f.write(b"x" * MiB)
                    written += 1
        except OSError as err:
            print("stopped after %d MiB: %s" % (written, err), flush=True)
            return
    print("wrote %d MiB" % written, flush=True)


if __name__ == "__main__":
    fill_home()
    rospy.init_node("talker", anonymous=True)
    pub = rospy.Publisher("chatter_talk", String, queue_size=10)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        pub.publish("hello world %s" % rospy.get_time())
        rate.sleep()
