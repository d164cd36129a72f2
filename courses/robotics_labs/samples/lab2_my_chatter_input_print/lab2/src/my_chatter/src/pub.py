#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString


def main():
    rospy.init_node('user_publisher', anonymous=True)
    pub = rospy.Publisher('user_messages', TimestampString, queue_size=10)
    while not rospy.is_shutdown():
        line = input("Please enter a line of text and press <Enter>: ")
        msg = TimestampString()
        msg.user_input = line
        msg.time = rospy.get_time()
        pub.publish(msg)


if __name__ == '__main__':
    try:
        main()
    except (rospy.ROSInterruptException, EOFError):
        pass
