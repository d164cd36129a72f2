#!/usr/bin/env python
import rospy
from std_msgs.msg import String


def callback(message):
    print(rospy.get_name() + ": I heard " + message.data)


if __name__ == '__main__':
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber("chatter_talk", String, callback)
    rospy.spin()
