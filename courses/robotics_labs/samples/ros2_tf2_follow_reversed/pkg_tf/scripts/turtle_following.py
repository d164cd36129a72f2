#!/usr/bin/env python3
import math

import rospy
import tf2_ros
from geometry_msgs.msg import Twist
from turtlesim.srv import Spawn


class TurtleFollowing:
    def __init__(self):
        self.source_frame = rospy.get_param("~source_frame", "turtle1")
        self.tf_buffer = tf2_ros.Buffer()
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        rospy.wait_for_service("spawn")
        spawner = rospy.ServiceProxy("spawn", Spawn)
        result = spawner(4.0, 2.0, 0.0, "turtle2")
        rospy.loginfo("Successfully spawned %s", result.name)
        self.publisher = rospy.Publisher("turtle2/cmd_vel", Twist, queue_size=1)
        self.timer = rospy.Timer(rospy.Duration(1.0), self.on_timer)

    def on_timer(self, event):
        try:
            trans = self.tf_buffer.lookup_transform(self.source_frame, "turtle2", rospy.Time())
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException) as ex:
            rospy.loginfo("Could not transform turtle2 to %s: %s", self.source_frame, ex)
            return
        msg = Twist()
        msg.angular.z = 1.0 * math.atan2(trans.transform.translation.y, trans.transform.translation.x)
        msg.linear.x = 0.5 * math.sqrt(trans.transform.translation.x ** 2 + trans.transform.translation.y ** 2)
        self.publisher.publish(msg)


if __name__ == "__main__":
    rospy.init_node("turtle_following")
    TurtleFollowing()
    rospy.spin()
