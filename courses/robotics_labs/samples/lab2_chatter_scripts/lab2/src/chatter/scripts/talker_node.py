#!/usr/bin/env python
# Lab 2 part 2: the example publisher, rewritten as a class
import rospy
from std_msgs.msg import String


class Talker(object):
    def __init__(self):
        self.pub = rospy.Publisher('/chatter_talk', String, queue_size=10)
        self.count = 0

    def run(self):
        r = rospy.Rate(5)
        while not rospy.is_shutdown():
            self.count += 1
            self.pub.publish(String("message number %d" % self.count))
            r.sleep()


if __name__ == '__main__':
    rospy.init_node('talker', anonymous=True)
    try:
        Talker().run()
    except rospy.ROSInterruptException:
        pass
