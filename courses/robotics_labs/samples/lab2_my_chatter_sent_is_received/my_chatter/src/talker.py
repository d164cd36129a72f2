#!/usr/bin/env python
import rospy
from my_chatter.msg import TimestampString


class UserTalker:
    def __init__(self):
        rospy.init_node('user_talker', anonymous=True)
        self.pub = rospy.Publisher('/user_messages', TimestampString, queue_size=10)

    def loop(self):
        while not rospy.is_shutdown():
            try:
                line = input('Please enter a line of text and press <Enter>: ')
            except EOFError:
                return
            stamp = rospy.get_time()
            self.pub.publish(TimestampString(message=line, timestamp=stamp))


if __name__ == '__main__':
    UserTalker().loop()
