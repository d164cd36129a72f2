#!/usr/bin/env python3
import rospy


class ParameterNode(object):
    def __init__(self):
        # "declare" robot_name: only if nobody set it before we started
        if not rospy.has_param("~robot_name"):
            rospy.set_param("~robot_name", "muto")
        self.timer = rospy.Timer(rospy.Duration(2.0), self.timer_callback)

    def timer_callback(self, event):
        robot_name_param = rospy.get_param("~robot_name")
        print("Hello %s!" % robot_name_param)


def main():
    rospy.init_node("param_declare")
    ParameterNode()
    rospy.spin()


if __name__ == "__main__":
    main()
