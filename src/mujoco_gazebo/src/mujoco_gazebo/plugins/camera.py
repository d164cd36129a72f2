"""gazebo_ros_camera on a <sensor type="camera">: <cameraName>/image_raw (rgb8) and
<cameraName>/camera_info at the sensor's rate, rendered (engine/camera.py) only while the
image has a subscriber. Size from the gazebo node's ~camera_width/~camera_height (default
320x240; 0 = the URDF's <image> size). Without OpenGL: one warning, camera_info only."""
from __future__ import annotations

import threading
import xml.etree.ElementTree as ET

import rospy
from sensor_msgs.msg import CameraInfo, Image
from std_msgs.msg import Header

from ..engine.camera import BodyCamera, CameraConfig, RenderUnavailable
from ..engine.urdf import PluginSpec
from ..engine.world import ModelEntry, World
from ..ros.conversions import stamp_from_sim
from .base import Plugin, ns_join, param_float, register


@register("libgazebo_ros_camera.so")
class CameraPlugin(Plugin):
    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        sensor, p = (spec.sensor if spec.sensor is not None else ET.Element("sensor")), spec.params
        rate = (param_float(p, "updateRate", 0.0)
                or param_float({"r": sensor.findtext("update_rate") or 30.0}, "r", 30.0))
        self.period = 1.0 / max(1e-3, rate)
        self.label = "%s: camera %s" % (entry.name, sensor.get("name", spec.name))
        try:
            width = int(rospy.get_param("~camera_width", 320)) or int(sensor.findtext("camera/image/width") or 320)
            height = int(rospy.get_param("~camera_height", 240)) or int(sensor.findtext("camera/image/height") or 240)
            self.config = CameraConfig(width=width, height=height,
                                       horizontal_fov=float(sensor.findtext("camera/horizontal_fov") or 1.047),
                                       near=float(sensor.findtext("camera/clip/near") or 0.1),
                                       far=float(sensor.findtext("camera/clip/far") or 100.0))
        except (TypeError, ValueError) as exc:
            self.config = CameraConfig()
            rospy.logwarn("%s: %s; using %dx%d" % (self.label, exc, self.config.width, self.config.height))
        self.camera = BodyCamera(self.config)
        self.model, self.link = entry.name, spec.reference
        self.frame = p.get("frameName", spec.reference or "")
        base = ns_join(entry.robot_namespace, p.get("cameraName", sensor.get("name", "camera")))
        self.image_pub = rospy.Publisher(ns_join(base, p.get("imageTopicName", "image_raw")), Image, queue_size=2)
        self.info_pub = rospy.Publisher(ns_join(base, p.get("cameraInfoTopicName", "camera_info")), CameraInfo,
                                        queue_size=2)
        self._handles += [self.image_pub, self.info_pub]
        self.rendering = True
        rospy.loginfo("%s: %dx%d at %g Hz on %s while subscribed" % (self.label, self.config.width,
                                                                   self.config.height, rate,
                                                                   self.image_pub.resolved_name))

    def _info(self, header: Header) -> CameraInfo:
        fx, fy, cx, cy = self.config.intrinsics()
        return CameraInfo(header=header, width=self.config.width, height=self.config.height,
                          distortion_model="plumb_bob", D=[0.0] * 5, K=[fx, 0, cx, 0, fy, cy, 0, 0, 1],
                          R=[1, 0, 0, 0, 1, 0, 0, 0, 1], P=[fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0])

    def update(self, world: World, now: float) -> None:
        want_image = self.rendering and self.image_pub.get_num_connections() > 0
        if not want_image and self.info_pub.get_num_connections() == 0:
            return
        header = Header(stamp=stamp_from_sim(now), frame_id=self.frame)
        link = world.link_id(self.model, self.link)
        if want_image and link >= 0:
            try:
                pixels = world.render(self.camera, link)
            except RenderUnavailable as exc:
                self.rendering = False
                rospy.logwarn("%s not rendered: %s; publishing camera_info only" % (self.label, exc))
            except Exception as exc:  # a GL/MuJoCo failure must not stop the simulation
                rospy.logerr_throttle(5.0, "%s: render failed: %s" % (self.label, exc))
            else:
                self.image_pub.publish(Image(header=header, height=pixels.shape[0], width=pixels.shape[1],
                                             encoding="rgb8", is_bigendian=0, step=pixels.shape[1] * 3,
                                             data=pixels.tobytes()))
        self.info_pub.publish(self._info(header))

    def close(self) -> None:
        super().close()
        self.camera.close()
