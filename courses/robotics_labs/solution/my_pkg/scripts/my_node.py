#!/usr/bin/env python3
"""my_node.py, node `drawer`: draws an arch of the angle sent on /draw_arch (Computer Exercise 1).

Subscribes /turtle1/pose and /draw_arch (std_msgs/Float32, radians in [0, 2pi]);
publishes /turtle1/cmd_vel; services /pause_drawing and /resume_drawing
(std_srvs/Trigger); calls /reset before each arch. Unlike the text's skeleton the
drawing is driven by pose messages, not a loop inside a callback, so pause/resume
and new requests are handled while drawing. A request while busy is ignored; a bad
angle (NaN, inf, outside [0, 2pi]) is always logged as an error, busy or not, and the
node keeps serving.
"""
import threading

import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Float32
from std_srvs.srv import Empty, Trigger, TriggerResponse
from turtlesim.msg import Pose

from my_pkg.arch import ArchError, ArchProgress, positive_setting

SETTLE_POSES = 3  # poses to skip after /reset: one published before the reset may still be queued


class Draw:
    def __init__(self) -> None:
        rospy.init_node("drawer")
        self.linear = self._setting("~linear_speed", 1.0)
        self.angular = self._setting("~angular_speed", 0.5)
        self.threshold = self._setting("~threshold", 0.02)
        self.lock = threading.Lock()
        self.is_busy = False
        self.allowed_to_draw = True
        self.progress = None
        self.settle = 0
        self.cmd_pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=1)
        self.reset = rospy.ServiceProxy("/reset", Empty)
        rospy.Service("pause_drawing", Trigger, self.pause_callback)
        rospy.Service("resume_drawing", Trigger, self.resume_callback)
        rospy.Subscriber("/turtle1/pose", Pose, self.pose_callback, queue_size=1)
        rospy.Subscriber("draw_arch", Float32, self.draw_arch_callback, queue_size=10)

    @staticmethod
    def _setting(name: str, default: float) -> float:
        value, problem = positive_setting(name, rospy.get_param(name, default), default)
        if problem:
            rospy.logwarn(problem)
        return value

    def draw_arch_callback(self, msg: Float32) -> None:
        try:  # a bad angle gets its error even while drawing
            progress = ArchProgress(msg.data, self.threshold)
        except ArchError as err:
            rospy.logerr(str(err))
            return
        with self.lock:
            if self.is_busy:
                rospy.loginfo("Currently drawing, new request is ignored")
                return
            rospy.loginfo("Recieved draw request")
            self.is_busy = True
        try:
            rospy.wait_for_service("/reset", 10)
            self.reset()
        except (rospy.ServiceException, rospy.ROSException) as err:
            rospy.logerr("could not reset turtlesim: %s" % err)
            with self.lock:
                self.is_busy = False
            return
        with self.lock:
            self.progress, self.settle, self.allowed_to_draw = progress, SETTLE_POSES, True
        rospy.loginfo("Start drawing")

    def pose_callback(self, msg: Pose) -> None:
        with self.lock:
            if self.progress is None:
                return
            if self.settle > 0:
                self.settle -= 1
                return
            if self.progress.update(msg.theta):
                self.progress = None
                self.is_busy = False
                finished = True
            else:
                finished = False
            drawing = self.allowed_to_draw
        if finished:
            self.cmd_pub.publish(Twist())
            rospy.loginfo("Finished drawing")
        elif drawing:
            twist = Twist()
            twist.linear.x = self.linear
            twist.angular.z = self.angular
            self.cmd_pub.publish(twist)

    def pause_callback(self, _req):
        with self.lock:
            self.allowed_to_draw = False
        self.cmd_pub.publish(Twist())
        return TriggerResponse(success=True, message="paused drawing")

    def resume_callback(self, _req):
        with self.lock:
            self.allowed_to_draw = True
        return TriggerResponse(success=True, message="resumed drawing")


if __name__ == "__main__":
    Draw()
    rospy.spin()
