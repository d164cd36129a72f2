#!/usr/bin/env python3
# Teleop for turtlesim / turtlebot, typed commands: w a s d then Enter (x = stop, q = quit)
import rospy
from geometry_msgs.msg import Twist


def read_scales():
    lin = rospy.get_param("linear_scale") if rospy.has_param("linear_scale") else 2.0
    ang = rospy.get_param("angular_scale") if rospy.has_param("angular_scale") else 2.0
    return float(lin), float(ang)


def main():
    rospy.init_node("mybot_teleop")
    topic = rospy.get_param("cmd_vel_topic_name", "turtle1/cmd_vel")
    print("Command sent to " + topic)
    pub = rospy.Publisher(topic, Twist, queue_size=10)
    while not rospy.is_shutdown():
        try:
            line = input("command (w/a/s/d, x stop, q quit) > ").strip().lower()
        except EOFError:
            break
        lin, ang = read_scales()
        msg = Twist()
        if line == "w":
            msg.linear.x = lin * 1.0
        elif line == "s":
            msg.linear.x = lin * -1.0
        elif line == "a":
            msg.angular.z = ang * 1.0
        elif line == "d":
            msg.angular.z = ang * -1.0
        elif line == "q":
            break
        elif line != "x":
            print("unknown command: %r" % line)
            continue
        pub.publish(msg)


if __name__ == "__main__":
    try:
        main()
    except rospy.ROSInterruptException:
        pass
