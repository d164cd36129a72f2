#!/usr/bin/env python3
"""listener.py: logs "I heard <data>" for every std_msgs/String that arrives on chatter."""
import rospy
from std_msgs.msg import String


def heard(message):
    rospy.loginfo("%s I heard %s", rospy.get_caller_id(), message.data)


def main():
    rospy.init_node("listener", anonymous=True)
    rospy.Subscriber("chatter", String, heard)
    rospy.spin()  # keeps the node alive until Ctrl-C: callbacks run on rospy's own threads


if __name__ == "__main__":
    main()
