#!/usr/bin/env python
import rospy
from std_msgs.msg import String


def talker():
    pub = rospy.Publisher('chatter_talk', String, queue_size=10)
    r = rospy.Rate(10)
    while not rospy.is_shutdown():
        pub.publish("hello world %s" % rospy.get_time())
        r.sleep()


if __name__ == '__main__':
    rospy.init_node('talker', anonymous=True)
    talker()
