"""gazebo_ros_diff_drive: cmd_vel -> wheel velocity servos (clamped to the robot's limits);
odom (nav_msgs/Odometry), TF odom -> base frame, and the wheels' joint_states at updateRate.
The maths is in engine/diffdrive.py (wheel speeds, wheel odometry) and engine/odometry.py."""
from __future__ import annotations

import math
import threading
from typing import Optional

import rospy
from geometry_msgs.msg import TransformStamped, Twist as TwistMsg
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage

from ..engine.diffdrive import DiffDriveGeometry, WheelOdometry, wheel_speeds
from ..engine.odometry import OdometryEstimate, from_encoders, from_ground_truth
from ..engine.urdf import PluginSpec
from ..engine.world import ModelEntry, World, WorldError
from ..ros.conversions import pose_to_msg, stamp_from_sim
from .base import Plugin, ns_join, param_float, register


def _flag(params: dict, key: str, default: str) -> bool:
    return params.get(key, default).lower() in ("1", "true")


@register("libgazebo_ros_diff_drive.so")
class DiffDrivePlugin(Plugin):
    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        p = spec.params
        self.model, self.lock, self.world = entry.name, lock, world
        self.period = 1.0 / max(1e-3, param_float(p, "updateRate", 30.0))
        self.geom = DiffDriveGeometry(wheel_separation=param_float(p, "wheelSeparation", 0.16),
                                      wheel_radius=param_float(p, "wheelDiameter", 0.066) / 2.0,
                                      max_linear=param_float(p, "maxLinearVelocity", math.inf),
                                      max_angular=param_float(p, "maxAngularVelocity", math.inf))
        self.torque = param_float(p, "wheelTorque", 10.0)
        self.left, self.right = p.get("leftJoint", "left_joint"), p.get("rightJoint", "right_joint")
        self.odom_frame = p.get("odometryFrame", "odom")
        self.base_frame = p.get("robotBaseFrame", "base_footprint")
        self.source = p.get("odometrySource", "world").lower()
        self.publish_tf = _flag(p, "publishOdomTF", p.get("publishTf", "true"))
        self.publish_joints = _flag(p, "publishWheelJointState", "true")
        ns = entry.robot_namespace
        self.odom_pub = rospy.Publisher(ns_join(ns, p.get("odometryTopic", "odom")), Odometry, queue_size=10)
        self.tf_pub = rospy.Publisher("/tf", TFMessage, queue_size=100)
        self.js_pub = rospy.Publisher(ns_join(ns, "joint_states"), JointState, queue_size=10)
        self._handles += [self.odom_pub, self.tf_pub, self.js_pub,
                          rospy.Subscriber(ns_join(ns, p.get("commandTopic", "cmd_vel")), TwistMsg, self._cmd,
                                           queue_size=1)]
        self.odometry = WheelOdometry(self.geom)
        self.origin = entry.spawn_pose
        self._last_time: Optional[float] = None
        self._stop(world)

    def _stop(self, world: World) -> None:
        for joint in (self.left, self.right):
            world.set_joint_velocity(self.model, joint, 0.0, 5.0, self.torque)

    def _cmd(self, msg: TwistMsg) -> None:
        if not all(math.isfinite(v) for v in (msg.linear.x, msg.angular.z)):
            rospy.logwarn_throttle(1.0, "%s: ignoring non-finite cmd_vel" % self.model)
            return
        left, right = wheel_speeds(self.geom, msg.linear.x, msg.angular.z)
        with self.lock:
            try:
                self.world.set_joint_velocity(self.model, self.left, left, 5.0, self.torque)
                self.world.set_joint_velocity(self.model, self.right, right, 5.0, self.torque)
            except WorldError as exc:
                rospy.logwarn_throttle(1.0, str(exc))

    def reset(self, world: World) -> None:
        super().reset(world)
        self.odometry.reset()
        self._last_time = None
        self.origin = world.models[self.model].spawn_pose
        self._stop(world)

    def _estimate(self, world: World) -> OdometryEstimate:
        if self.source == "encoder":
            return from_encoders(self.odometry)
        pose, twist = world.get_model_state(self.model)
        return from_ground_truth(pose, twist, self.origin)

    def update(self, world: World, now: float) -> None:
        pos, vel, eff = world.joint_states(self.model, [self.left, self.right])
        dt = 0.0 if self._last_time is None else now - self._last_time
        self._last_time = now
        self.odometry.update(pos[0], pos[1], dt)
        estimate = self._estimate(world)
        odom = Odometry()
        odom.header.stamp = stamp_from_sim(now)
        odom.header.frame_id = self.odom_frame
        odom.child_frame_id = self.base_frame
        odom.pose.pose = pose_to_msg(estimate.pose)
        twist = odom.twist.twist
        twist.linear.x, twist.linear.y, twist.linear.z = (float(v) for v in estimate.linear)
        twist.angular.x, twist.angular.y, twist.angular.z = (float(v) for v in estimate.angular)
        self.odom_pub.publish(odom)
        if self.publish_tf:
            tf = TransformStamped()
            tf.header = odom.header
            tf.child_frame_id = self.base_frame
            p = odom.pose.pose.position
            tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = p.x, p.y, p.z
            tf.transform.rotation = odom.pose.pose.orientation
            self.tf_pub.publish(TFMessage([tf]))
        if self.publish_joints:
            js = JointState(name=[self.left, self.right], position=pos, velocity=vel, effort=eff)
            js.header.stamp = odom.header.stamp
            self.js_pub.publish(js)
