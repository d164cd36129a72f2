#!/usr/bin/env python3
"""example_pub.py: publishes a greeting with the current time on /chatter_talk, 10 times a second
(Lab 2, section 2: the example publisher)."""
import rospy
from std_msgs.msg import String


def talker() -> None:
    # A publisher on /chatter_talk carrying std_msgs/String; queue_size bounds the outgoing buffer.
    pub = rospy.Publisher("chatter_talk", String, queue_size=10)
    rate = rospy.Rate(10)  # 10 Hz
    while not rospy.is_shutdown():
        pub.publish("hello world %s" % rospy.get_time())
        rate.sleep()


if __name__ == "__main__":
    # anonymous=True: several publishers can run at once (the text asks what happens then).
    rospy.init_node("talker", anonymous=True)
    try:
        talker()
    except rospy.ROSInterruptException:
        pass
