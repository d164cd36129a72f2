#!/usr/bin/env python3
import rospy


class ParameterNode(object):
    def __init__(self):
        self.robot_name = rospy.get_param("~robot_name", "muto")
        self.timer = rospy.Timer(rospy.Duration(2.0), self.timer_callback)

    def timer_callback(self, event):
        rospy.loginfo("Hello %s!" % self.robot_name)


if __name__ == "__main__":
    rospy.init_node("param_declare")
    ParameterNode()
    rospy.spin()
