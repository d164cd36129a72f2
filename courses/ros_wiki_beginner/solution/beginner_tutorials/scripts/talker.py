#!/usr/bin/env python3
"""talker.py: says "hello world <time>" on the topic chatter (std_msgs/String), ten times a second."""
import rospy
from std_msgs.msg import String


def main():
    rospy.init_node("talker", anonymous=True)
    chatter = rospy.Publisher("chatter", String, queue_size=10)
    every_tenth = rospy.Rate(10)
    while not rospy.is_shutdown():
        words = "hello world %s" % rospy.get_time()
        rospy.loginfo(words)
        chatter.publish(String(data=words))
        every_tenth.sleep()


if __name__ == "__main__":
    try:
        main()
    except rospy.ROSInterruptException:
        pass
