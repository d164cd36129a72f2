"""gazebo_ros_imu (and gazebo_ros_imu_sensor): sensor_msgs/Imu of a link, the readings from
engine/imu.py (orientation in the world, angular velocity and linear acceleration in the
link's axes, gravity included)."""
from __future__ import annotations

import threading

import rospy
from sensor_msgs.msg import Imu

from ..engine.imu import ImuModel
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
        self.imu = ImuModel()

    def update(self, world: World, now: float) -> None:
        link = world.link_id(self.model, self.link)
        if link < 0:
            return
        reading = self.imu.sample(now, world.body_pose(link), world.body_twist(link), world.gravity)
        msg = Imu()
        msg.header.stamp = stamp_from_sim(now)
        msg.header.frame_id = self.frame
        o, w, a = msg.orientation, msg.angular_velocity, msg.linear_acceleration
        o.w, o.x, o.y, o.z = (float(v) for v in reading.orientation)
        w.x, w.y, w.z = (float(v) for v in reading.angular_velocity)
        a.x, a.y, a.z = (float(v) for v in reading.linear_acceleration)
        self.pub.publish(msg)
