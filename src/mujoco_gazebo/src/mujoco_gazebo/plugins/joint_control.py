"""gazebo_ros_control as the RRBot tutorial's controllers name it: per joint,
<ns>/<joint>_position_controller/command, _velocity_controller/command and
_effort_controller/command (std_msgs/Float64), and <ns>/joint_states at 50 Hz.
A joint stays passive (falls under gravity) until its first command."""
from __future__ import annotations

import math
import threading

import rospy
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

from ..engine.urdf import PluginSpec
from ..engine.world import ModelEntry, World, WorldError
from ..ros.conversions import stamp_from_sim
from .base import Plugin, ns_join, register


@register("libgazebo_ros_control.so")
class JointControlPlugin(Plugin):
    period = 1.0 / 50.0

    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        self.model, self.joints, self.lock, self.world = entry.name, list(entry.joints), lock, world
        self.ns = spec.params.get("robotNamespace") or entry.robot_namespace or entry.name
        self.pub = rospy.Publisher(ns_join(self.ns, "joint_states"), JointState, queue_size=10)
        self._handles.append(self.pub)
        for joint in self.joints:
            for kind in ("position", "velocity", "effort"):
                topic = ns_join(self.ns, "%s_%s_controller/command" % (joint, kind))
                self._handles.append(rospy.Subscriber(topic, Float64, self._command, (joint, kind), queue_size=10))

    def _gain(self, joint: str, kind: str, name: str, default: float) -> float:
        try:
            return float(rospy.get_param(ns_join(self.ns, "%s_%s_controller/pid/%s" % (joint, kind, name)), default))
        except (TypeError, ValueError):
            return default

    def _command(self, msg: Float64, args) -> None:
        joint, kind = args
        if not math.isfinite(msg.data):
            rospy.logwarn_throttle(1.0, "%s: ignoring non-finite %s command for %s" % (self.model, kind, joint))
            return
        with self.lock:
            try:
                if kind == "position":
                    self.world.set_joint_position(self.model, joint, msg.data, self._gain(joint, kind, "p", 100.0),
                                                  self._gain(joint, kind, "d", 10.0))
                elif kind == "velocity":
                    self.world.set_joint_velocity(self.model, joint, msg.data, self._gain(joint, kind, "p", 10.0))
                else:
                    self.world.set_joint_effort(self.model, joint, msg.data)
            except WorldError as exc:
                rospy.logwarn_throttle(1.0, str(exc))

    def update(self, world: World, now: float) -> None:
        pos, vel, eff = world.joint_states(self.model, self.joints)
        msg = JointState(name=self.joints, position=pos, velocity=vel, effort=eff)
        msg.header.stamp = stamp_from_sim(now)
        self.pub.publish(msg)
