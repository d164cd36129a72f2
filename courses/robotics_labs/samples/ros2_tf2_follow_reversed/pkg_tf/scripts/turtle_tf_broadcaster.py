#!/usr/bin/env python3
import math

import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped
from turtlesim.msg import Pose


def quaternion_from_euler(roll, pitch, yaw):
    cy, sy = math.cos(yaw * 0.5), math.sin(yaw * 0.5)
    cp, sp = math.cos(pitch * 0.5), math.sin(pitch * 0.5)
    cr, sr = math.cos(roll * 0.5), math.sin(roll * 0.5)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


class TurtleTFBroadcaster:
    def __init__(self):
        self.turtlename = rospy.get_param("~turtlename", "turtle")
        self.tf_broadcaster = tf2_ros.TransformBroadcaster()
        rospy.Subscriber("/%s/pose" % self.turtlename, Pose, self.turtle_pose_callback, queue_size=1)

    def turtle_pose_callback(self, msg):
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = "world"
        t.child_frame_id = self.turtlename
        t.transform.translation.x = msg.x
        t.transform.translation.y = msg.y
        q = quaternion_from_euler(0, 0, msg.theta)
        t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = q
        self.tf_broadcaster.sendTransform(t)


if __name__ == "__main__":
    rospy.init_node("turtle_tf_broadcaster")
    TurtleTFBroadcaster()
    rospy.spin()
