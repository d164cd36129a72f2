"""ROS faces of the robot plugins a URDF's <gazebo> blocks ask for (gazebo_ros_control,
gazebo_ros_diff_drive, gazebo_ros_laser, gazebo_ros_imu, gazebo_ros_camera): thin wiring from topics to the
World's actuators and from the World's state to messages. All `update` calls happen with
the world lock held, at the plugin's own rate in simulated time."""
from __future__ import annotations

import math
import threading
import xml.etree.ElementTree as ET
from typing import Callable, List, Optional

import mujoco
import numpy as np
import rospy
from geometry_msgs.msg import TransformStamped, Twist as TwistMsg
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, Image, Imu, JointState, LaserScan
from std_msgs.msg import Float64, Header
from tf2_msgs.msg import TFMessage

from .camera import BodyCamera, CameraConfig, RenderUnavailable
from .conversions import stamp_from_sim
from .diffdrive import DiffDriveGeometry, WheelOdometry, wheel_speeds
from .frames import Pose, quat_conj, quat_from_rpy, rotate, yaw_of
from .lidar import Lidar, ScanConfig
from .urdf import PluginSpec
from .world import ModelEntry, World, WorldError


def _ns_join(ns: str, name: str) -> str:
    if name.startswith("/"):
        return name
    ns = ns.strip("/")
    return "/%s/%s" % (ns, name) if ns else "/" + name


def _float(params: dict, key: str, default: float) -> float:
    try:
        return float(params.get(key, default))
    except ValueError:
        return default


class RobotPlugin:
    """Base: a period in simulated seconds and the bookkeeping to run at it."""

    period = 0.0

    def __init__(self) -> None:
        self._next = 0.0
        self._handles: List = []

    def due(self, now: float) -> bool:
        if now + 1e-9 < self._next:
            return False
        self._next = now + self.period if now - self._next > self.period else self._next + self.period
        return True

    def update(self, world: World, now: float) -> None:
        raise NotImplementedError

    def reset(self, world: World) -> None:
        self._next = 0.0

    def close(self) -> None:
        for handle in self._handles:
            handle.unregister()
        self._handles = []


def _stamp(now: float) -> rospy.Time:
    return stamp_from_sim(now)


class JointControlPlugin(RobotPlugin):
    """gazebo_ros_control as the RRBot tutorial's controllers name it: per joint,
    <ns>/<joint>_position_controller/command, _velocity_controller/command and
    _effort_controller/command (std_msgs/Float64), and <ns>/joint_states at 50 Hz.
    A joint stays passive (falls under gravity) until its first command."""

    period = 1.0 / 50.0

    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        self.model, self.joints, self.lock, self.world = entry.name, list(entry.joints), lock, world
        self.ns = spec.params.get("robotNamespace") or entry.robot_namespace or entry.name
        self.pub = rospy.Publisher(_ns_join(self.ns, "joint_states"), JointState, queue_size=10)
        self._handles.append(self.pub)
        for joint in self.joints:
            for kind in ("position", "velocity", "effort"):
                topic = _ns_join(self.ns, "%s_%s_controller/command" % (joint, kind))
                self._handles.append(rospy.Subscriber(topic, Float64, self._command, (joint, kind), queue_size=10))

    def _gain(self, joint: str, kind: str, name: str, default: float) -> float:
        try:
            return float(rospy.get_param(_ns_join(self.ns, "%s_%s_controller/pid/%s" % (joint, kind, name)), default))
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
        msg.header.stamp = _stamp(now)
        self.pub.publish(msg)


class DiffDrivePlugin(RobotPlugin):
    """gazebo_ros_diff_drive: cmd_vel -> wheel velocity servos (clamped to the robot's limits);
    odom (nav_msgs/Odometry), TF odom -> base frame, and the wheels' joint_states at updateRate."""

    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        p = spec.params
        self.model, self.lock, self.world = entry.name, lock, world
        self.period = 1.0 / max(1e-3, _float(p, "updateRate", 30.0))
        self.geom = DiffDriveGeometry(wheel_separation=_float(p, "wheelSeparation", 0.16),
                                      wheel_radius=_float(p, "wheelDiameter", 0.066) / 2.0,
                                      max_linear=_float(p, "maxLinearVelocity", math.inf),
                                      max_angular=_float(p, "maxAngularVelocity", math.inf))
        self.torque = _float(p, "wheelTorque", 10.0)
        self.left, self.right = p.get("leftJoint", "left_joint"), p.get("rightJoint", "right_joint")
        self.odom_frame = p.get("odometryFrame", "odom")
        self.base_frame = p.get("robotBaseFrame", "base_footprint")
        self.source = p.get("odometrySource", "world").lower()
        self.publish_tf = p.get("publishOdomTF", p.get("publishTf", "true")).lower() in ("1", "true")
        self.publish_joints = p.get("publishWheelJointState", "true").lower() in ("1", "true")
        ns = entry.robot_namespace
        self.odom_pub = rospy.Publisher(_ns_join(ns, p.get("odometryTopic", "odom")), Odometry, queue_size=10)
        self.tf_pub = rospy.Publisher("/tf", TFMessage, queue_size=100)
        self.js_pub = rospy.Publisher(_ns_join(ns, "joint_states"), JointState, queue_size=10)
        self._handles += [self.odom_pub, self.tf_pub, self.js_pub,
                          rospy.Subscriber(_ns_join(ns, p.get("commandTopic", "cmd_vel")), TwistMsg, self._cmd, queue_size=1)]
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

    def update(self, world: World, now: float) -> None:
        pos, vel, eff = world.joint_states(self.model, [self.left, self.right])
        dt = 0.0 if self._last_time is None else now - self._last_time
        self._last_time = now
        self.odometry.update(pos[0], pos[1], dt)
        odom = Odometry()
        odom.header.stamp = _stamp(now)
        odom.header.frame_id = self.odom_frame
        odom.child_frame_id = self.base_frame
        if self.source == "encoder":
            x, y, z, q = self.odometry.x, self.odometry.y, 0.0, quat_from_rpy(0, 0, self.odometry.yaw)
            v, w = self.odometry.linear, self.odometry.angular
            odom.twist.twist.linear.x, odom.twist.twist.angular.z = v, w
        else:  # ground truth relative to the spawn pose
            pose, twist = world.get_model_state(self.model)
            rel = pose.relative_to(self.origin)
            (x, y, z), q = rel.position, rel.orientation
            body_lin = rotate(quat_conj(pose.orientation), twist.linear)
            body_ang = rotate(quat_conj(pose.orientation), twist.angular)
            odom.twist.twist.linear.x, odom.twist.twist.linear.y = body_lin[0], body_lin[1]
            odom.twist.twist.angular.z = body_ang[2]
        odom.pose.pose.position.x, odom.pose.pose.position.y, odom.pose.pose.position.z = x, y, z
        o = odom.pose.pose.orientation
        o.w, o.x, o.y, o.z = (float(c) for c in q)
        self.odom_pub.publish(odom)
        if self.publish_tf:
            tf = TransformStamped()
            tf.header = odom.header
            tf.child_frame_id = self.base_frame
            tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = x, y, z
            tf.transform.rotation = odom.pose.pose.orientation
            self.tf_pub.publish(TFMessage([tf]))
        if self.publish_joints:
            js = JointState(name=[self.left, self.right], position=pos, velocity=vel, effort=eff)
            js.header.stamp = odom.header.stamp
            self.js_pub.publish(js)


class LaserPlugin(RobotPlugin):
    """gazebo_ros_laser on a <sensor type="ray">: sensor_msgs/LaserScan from mj_multiRay."""

    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        sensor = spec.sensor
        self.period = 1.0 / max(1e-3, float(sensor.findtext("update_rate") or 10.0))
        h = "ray/scan/horizontal/"
        cfg = ScanConfig(samples=int(float(sensor.findtext(h + "samples") or 360)),
                         min_angle=float(sensor.findtext(h + "min_angle") or 0.0),
                         max_angle=float(sensor.findtext(h + "max_angle") or 2 * math.pi),
                         range_min=float(sensor.findtext("ray/range/min") or 0.1),
                         range_max=float(sensor.findtext("ray/range/max") or 10.0))
        self.lidar = Lidar(cfg)
        self.body = "%s::%s" % (entry.name, spec.reference)
        self.frame = spec.params.get("frameName", spec.reference or "")
        self.pub = rospy.Publisher(_ns_join(entry.robot_namespace, spec.params.get("topicName", "scan")),
                                   LaserScan, queue_size=5)
        self._handles.append(self.pub)

    def update(self, world: World, now: float) -> None:
        if self.pub.get_num_connections() == 0:
            return
        bid = mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, self.body)
        if bid < 0:
            return
        cfg = self.lidar.config
        msg = LaserScan(angle_min=cfg.min_angle, angle_max=cfg.max_angle, angle_increment=cfg.angle_increment,
                        time_increment=0.0, scan_time=self.period, range_min=cfg.range_min, range_max=cfg.range_max)
        msg.header.stamp = _stamp(now)
        msg.header.frame_id = self.frame
        msg.ranges = self.lidar.scan(world.model, world.data, bid).tolist()
        self.pub.publish(msg)


class ImuPlugin(RobotPlugin):
    """gazebo_ros_imu: orientation (world), angular velocity and linear acceleration (body axes,
    gravity included, as an accelerometer reads it)."""

    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        p = spec.params
        rate = _float(p, "updateRate", _float(p, "updateRateHZ", 200.0))
        self.period = 1.0 / rate if rate > 0 else world.timestep
        self.body = "%s::%s" % (entry.name, p.get("bodyName", spec.reference or ""))
        self.frame = p.get("frameName", p.get("bodyName", ""))
        self.pub = rospy.Publisher(_ns_join(entry.robot_namespace, p.get("topicName", "imu")), Imu, queue_size=10)
        self._handles.append(self.pub)
        self._last: Optional[tuple] = None

    def update(self, world: World, now: float) -> None:
        bid = mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, self.body)
        if bid < 0:
            return
        pose, twist = world.body_pose(bid), world.body_twist(bid)
        acc = np.zeros(3)
        if self._last is not None and now > self._last[0]:
            acc = (twist.linear - self._last[1]) / (now - self._last[0])
        self._last = (now, twist.linear.copy())
        acc = acc - np.array(world.model.opt.gravity)
        inv = quat_conj(pose.orientation)
        msg = Imu()
        msg.header.stamp = _stamp(now)
        msg.header.frame_id = self.frame
        msg.orientation.w, msg.orientation.x, msg.orientation.y, msg.orientation.z = (float(v) for v in pose.orientation)
        w = rotate(inv, twist.angular)
        a = rotate(inv, acc)
        msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = (float(v) for v in w)
        msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = (float(v) for v in a)
        self.pub.publish(msg)


class CameraPlugin(RobotPlugin):
    """gazebo_ros_camera on a <sensor type="camera">: <cameraName>/image_raw (rgb8) and
    <cameraName>/camera_info at the sensor's rate, rendered only while the image has a
    subscriber. Size from the gazebo node's ~camera_width/~camera_height (default 320x240;
    0 = the URDF's <image> size). Without OpenGL: one warning, camera_info only."""

    def __init__(self, entry: ModelEntry, spec: PluginSpec, lock: threading.Lock, world: World) -> None:
        super().__init__()
        sensor, p = (spec.sensor if spec.sensor is not None else ET.Element("sensor")), spec.params
        rate = _float(p, "updateRate", 0.0) or _float({"r": sensor.findtext("update_rate") or 30.0}, "r", 30.0)
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
        self.body = "%s::%s" % (entry.name, spec.reference)
        self.frame = p.get("frameName", spec.reference or "")
        base = _ns_join(entry.robot_namespace, p.get("cameraName", sensor.get("name", "camera")))
        self.image_pub = rospy.Publisher(_ns_join(base, p.get("imageTopicName", "image_raw")), Image, queue_size=2)
        self.info_pub = rospy.Publisher(_ns_join(base, p.get("cameraInfoTopicName", "camera_info")), CameraInfo,
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
        header = Header(stamp=_stamp(now), frame_id=self.frame)
        bid = mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, self.body)
        if want_image and bid >= 0:
            try:
                pixels = self.camera.render(world.model, world.data, bid)
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


PLUGINS = {
    "libgazebo_ros_control.so": JointControlPlugin,
    "libgazebo_ros_diff_drive.so": DiffDrivePlugin,
    "libgazebo_ros_laser.so": LaserPlugin,
    "libgazebo_ros_gpu_laser.so": LaserPlugin,
    "libgazebo_ros_imu.so": ImuPlugin,
    "libgazebo_ros_imu_sensor.so": ImuPlugin,
    "libgazebo_ros_camera.so": CameraPlugin,
}


def make_plugins(entry: ModelEntry, lock: threading.Lock, world: World,
                 extra: Optional[Callable[[ModelEntry, PluginSpec], Optional[RobotPlugin]]] = None) -> List[RobotPlugin]:
    """Instantiate the ROS plugins a model's URDF asks for; unknown ones are logged and skipped."""
    out: List[RobotPlugin] = []
    for spec in entry.plugins:
        cls = PLUGINS.get(spec.filename)
        plugin = cls(entry, spec, lock, world) if cls else (extra(entry, spec) if extra else None)
        if plugin is None:
            rospy.loginfo("%s: plugin %s (%s) not simulated" % (entry.name, spec.name, spec.filename))
            continue
        out.append(plugin)
    return out
