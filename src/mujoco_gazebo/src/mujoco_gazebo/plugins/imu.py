"""gazebo_ros_imu (and gazebo_ros_imu_sensor): sensor_msgs/Imu of a link: orientation in the
world, angular velocity and linear acceleration in the link's axes, gravity included (as an
accelerometer reads it)."""
from __future__ import annotations

import threading
from typing import Optional

import numpy as np

import rospy
from sensor_msgs.msg import Imu

from ..engine.frames import quat_conj, rotate
from ..engine.urdf import PluginSpec
from ..engine.world import ModelEntry, World
from ..ros.conversions import stamp_from_sim
from .base import Plugin, ns_join, param_float, register


@register("libgazebo_ros_imu.so", "libgazebo_ros_imu_sensor.so")
class ImuPlugin(Plugin):
    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        p = spec.params
        rate = param_float(p, "updateRate", param_float(p, "updateRateHZ", 200.0))
        self.period = 1.0 / rate if rate > 0 else world.timestep
        self.model, self.link = entry.name, p.get("bodyName", spec.reference or "")
        self.frame = p.get("frameName", p.get("bodyName", ""))
        self.pub = rospy.Publisher(ns_join(entry.robot_namespace, p.get("topicName", "imu")), Imu, queue_size=10)
        self._handles.append(self.pub)
        self._last: Optional[tuple] = None

    def update(self, world: World, now: float) -> None:
        link = world.link_id(self.model, self.link)
        if link < 0:
            return
        pose, twist = world.body_pose(link), world.body_twist(link)
        acc = np.zeros(3)
        if self._last is not None and now > self._last[0]:
            acc = (twist.linear - self._last[1]) / (now - self._last[0])
        self._last = (now, twist.linear.copy())
        acc = acc - world.gravity
        inv = quat_conj(pose.orientation)
        msg = Imu()
        msg.header.stamp = stamp_from_sim(now)
        msg.header.frame_id = self.frame
        msg.orientation.w, msg.orientation.x, msg.orientation.y, msg.orientation.z = (float(v) for v in pose.orientation)
        w = rotate(inv, twist.angular)
        a = rotate(inv, acc)
        msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = (float(v) for v in w)
        msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = (float(v) for v in a)
        self.pub.publish(msg)
