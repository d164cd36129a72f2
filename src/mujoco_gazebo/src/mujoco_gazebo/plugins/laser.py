"""gazebo_ros_laser (and its GPU twin) on a <sensor type="ray">: sensor_msgs/LaserScan from
the World's ray casts (engine/lidar.py), published only while someone listens."""
from __future__ import annotations

import math
import threading

import rospy
from sensor_msgs.msg import LaserScan

from ..engine.lidar import Lidar, ScanConfig
from ..engine.urdf import PluginSpec
from ..engine.world import ModelEntry, World
from ..ros.conversions import stamp_from_sim
from .base import Plugin, ns_join, register


def scan_config(sensor) -> ScanConfig:
    """The <ray> block of a Gazebo ray sensor (gazebo's defaults where a value is missing)."""
    h = "ray/scan/horizontal/"
    return ScanConfig(samples=int(float(sensor.findtext(h + "samples") or 360)),
                      min_angle=float(sensor.findtext(h + "min_angle") or 0.0),
                      max_angle=float(sensor.findtext(h + "max_angle") or 2 * math.pi),
                      range_min=float(sensor.findtext("ray/range/min") or 0.1),
                      range_max=float(sensor.findtext("ray/range/max") or 10.0))


@register("libgazebo_ros_laser.so", "libgazebo_ros_gpu_laser.so")
class LaserPlugin(Plugin):
    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        sensor = spec.sensor
        self.period = 1.0 / max(1e-3, float(sensor.findtext("update_rate") or 10.0))
        self.lidar = Lidar(scan_config(sensor))
        self.model, self.link = entry.name, spec.reference
        self.frame = spec.params.get("frameName", spec.reference or "")
        self.pub = rospy.Publisher(ns_join(entry.robot_namespace, spec.params.get("topicName", "scan")),
                                   LaserScan, queue_size=5)
        self._handles.append(self.pub)

    def update(self, world: World, now: float) -> None:
        if self.pub.get_num_connections() == 0:
            return
        link = world.link_id(self.model, self.link)
        if link < 0:
            return
        cfg = self.lidar.config
        msg = LaserScan(angle_min=cfg.min_angle, angle_max=cfg.max_angle, angle_increment=cfg.angle_increment,
                        time_increment=0.0, scan_time=self.period, range_min=cfg.range_min, range_max=cfg.range_max)
        msg.header.stamp = stamp_from_sim(now)
        msg.header.frame_id = self.frame
        msg.ranges = world.scan(self.lidar, link).tolist()
        self.pub.publish(msg)
