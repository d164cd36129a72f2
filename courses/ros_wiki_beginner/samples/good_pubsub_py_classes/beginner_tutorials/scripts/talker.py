#!/usr/bin/env python3
import rospy
from std_msgs.msg import String


class Talker:
    def __init__(self, hz=20):
        self.pub = rospy.Publisher("/chatter", String, queue_size=5)
        self.rate = rospy.Rate(hz)

    def run(self):
        while not rospy.is_shutdown():
            self.pub.publish("hello world {}".format(rospy.get_time()))
            self.rate.sleep()


if __name__ == "__main__":
    rospy.init_node("talker")
    try:
        Talker().run()
    except rospy.ROSInterruptException:
        pass
