#!/usr/bin/env python3
"""Lab 2, section 2: the talker. Sends a numbered greeting on /chatter_talk from a timer,
so the main thread only waits for shutdown."""
import rospy
from std_msgs.msg import String


class Talker:
    def __init__(self, period):
        self.sent = 0
        self.prefix = rospy.get_param("~prefix", "hello from " + rospy.get_name())
        self.publisher = rospy.Publisher("/chatter_talk", String, queue_size=5)
        self.timer = rospy.Timer(rospy.Duration(period), self.tick)

    def tick(self, event):
        self.sent += 1
        text = "%s #%d at %.2f" % (self.prefix, self.sent, event.current_real.to_sec())
        self.publisher.publish(String(data=text))
        if self.sent % 50 == 0:
            rospy.loginfo("%d greetings sent so far", self.sent)

    def stop(self):
        self.timer.shutdown()
        rospy.loginfo("talker stopping after %d messages", self.sent)


def main():
    rospy.init_node("alice_talker", anonymous=True)
    talker = Talker(rospy.get_param("~period", 0.2))
    rospy.on_shutdown(talker.stop)
    rospy.spin()


if __name__ == "__main__":
    main()
