#!/usr/bin/env python3
"""mybot_color: red pen in the corners of turtlesim, background colour by side (UPMC part 1, part B).

Subscribes /turtle1/pose; calls /turtle1/set_pen only when the turtle enters or
leaves a corner region (~corner_margin, 2.0 m); when it comes within
~side_margin (1.0 m) of a side, sets /turtlesim/background_r/g/b to that side's
colour and calls /clear (back to the default background when it leaves).
~change_background (true) turns the background part off.
"""
import math

import rospy
from std_srvs.srv import Empty
from turtlesim.msg import Pose
from turtlesim.srv import SetPen

from mybot_color_core.regions import DEFAULT_PEN, ENTER, RED_PEN, CornerWatcher, SideWatcher


class ColorNode:
    def __init__(self) -> None:
        self.corners = CornerWatcher(float(rospy.get_param("~corner_margin", 2.0)))
        self.sides = SideWatcher(float(rospy.get_param("~side_margin", 1.0)))
        self.change_background = bool(rospy.get_param("~change_background", True))
        self.background_ns = rospy.get_param("~turtlesim_node", "/turtlesim")
        rospy.wait_for_service("/turtle1/set_pen")
        self.change_pen_color = rospy.ServiceProxy("/turtle1/set_pen", SetPen)
        self.clear = rospy.ServiceProxy("/clear", Empty)
        self.sub = rospy.Subscriber("/turtle1/pose", Pose, self.read_pose_callback, queue_size=1)

    def read_pose_callback(self, msg: Pose) -> None:
        if not (math.isfinite(msg.x) and math.isfinite(msg.y)):
            rospy.logwarn_throttle(1.0, "ignoring a non-finite pose")
            return
        rospy.loginfo_throttle(1.0, "Current position: x=%.2f; y=%.2f" % (msg.x, msg.y))
        try:
            event = self.corners.update(msg.x, msg.y)
            if event is not None:
                r, g, b, width = RED_PEN if event == ENTER else DEFAULT_PEN
                self.change_pen_color(r, g, b, width, False)
            background = self.sides.update(msg.x, msg.y) if self.change_background else None
            if background is not None:
                for channel, value in zip("rgb", background):
                    rospy.set_param("%s/background_%s" % (self.background_ns, channel), value)
                self.clear()
        except (rospy.ServiceException, rospy.ROSException) as err:
            rospy.logwarn_throttle(1.0, "turtlesim service call failed: %s" % err)


if __name__ == "__main__":
    rospy.init_node("mybot_color", anonymous=False, log_level=rospy.INFO, disable_signals=False)
    try:
        ColorNode()
        rospy.spin()
    except rospy.ROSInterruptException:
        pass
