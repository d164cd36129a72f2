"""The turtlesim node: wires TurtleFrame to ROS topics, services and parameters.

Interfaces match upstream turtlesim (per turtle: cmd_vel, pose, color_sensor,
set_pen, teleport_absolute, teleport_relative; global: clear, reset, spawn, kill;
private params background_r/g/b). Beyond upstream: ~image (the rendered canvas,
published only while someone subscribes, and only when it changed), ~scene and ~canvas (the
canvas as drawing commands and a snapshot, for the lab page that draws it itself:
turtlesim.scene) and ~snapshot (writes a PNG).
"""
from __future__ import annotations

import os
import threading
import time
from typing import Dict, Optional

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import Image
from std_msgs.msg import String
from std_srvs.srv import Empty, EmptyResponse, Trigger, TriggerResponse

from turtlesim.canvas import RGB, Canvas, rgb888_bytes
from turtlesim.constants import BACKGROUND_PARAMS, CENTRE, DEFAULT_BACKGROUND_RGB, TICK, WALL_WARNING
from turtlesim.fanout import TickPublisher
from turtlesim.frame import TurtleError, TurtleFrame, TurtleUpdate
from turtlesim.msg import Color, Pose
from turtlesim.scene import FrameGate, SceneLog, snapshot_json
from turtlesim.srv import (Kill, KillResponse, SetPen, SetPenResponse, Spawn, SpawnResponse,
                           TeleportAbsolute, TeleportAbsoluteResponse, TeleportRelative,
                           TeleportRelativeResponse)
from turtlesim.ticker import Ticker

POSE_LAYOUT = "<5f"  # turtlesim/Pose on the wire: x, y, theta, linear_velocity, angular_velocity
COLOR_LAYOUT = "<3B"  # turtlesim/Color: r, g, b
UNHEARD_TICKS_PER_WAKE = 2  # a wake-up costs ~77 us of CPU here, a tick's own work ~20 us
SCENE_GRACE_S = 10.0  # how long after a ~canvas call lines are recorded for a subscriber still connecting
SCENE_QUEUE = 50  # updates a slow subscriber may have waiting (one it misses makes the page ask ~canvas)


def private_params() -> dict:
    """The node's private parameters (`~name` -> value), read in one call to the master."""
    params = rospy.get_param("~", {})
    return params if isinstance(params, dict) else {}


def background_from(params: dict) -> RGB:
    """The background colour from the background_r/g/b params, each forced into 0..255."""
    values = []
    for param, default in zip(BACKGROUND_PARAMS, DEFAULT_BACKGROUND_RGB):
        value = params.get(param, default)
        try:
            values.append(min(max(int(value), 0), 255))
        except (TypeError, ValueError, OverflowError):  # OverflowError: int(inf)
            rospy.logwarn("~%s=%r is not a number; using %d" % (param, value, default))
            values.append(default)
    return tuple(values)


class TurtleInterface:
    """The ROS face of one turtle, under the namespace of its name."""

    def __init__(self, name: str, sim: "TurtlesimNode") -> None:
        self.name = name
        self._sim = sim
        # Published every tick by the ticker itself: packed once, no thread per subscriber (fanout).
        self.pose_pub = TickPublisher(name + "/pose", Pose, POSE_LAYOUT)
        self.colour_pub = TickPublisher(name + "/color_sensor", Color, COLOR_LAYOUT)
        self.cmd_sub = rospy.Subscriber(name + "/cmd_vel", Twist, self._on_cmd_vel, queue_size=1)
        self.services = [
            rospy.Service(name + "/set_pen", SetPen, self._on_set_pen),
            rospy.Service(name + "/teleport_absolute", TeleportAbsolute, self._on_teleport_absolute),
            rospy.Service(name + "/teleport_relative", TeleportRelative, self._on_teleport_relative),
        ]

    def listened_to(self) -> bool:
        """Whether anyone takes this turtle's pose or colour sensor, which go out every tick."""
        return self.pose_pub.has_subscribers() or self.colour_pub.has_subscribers()

    def wants_colour(self) -> bool:
        """Whether anyone listens to the colour sensor (nobody: the tick need not read it)."""
        return self.colour_pub.has_subscribers()

    def publish(self, update: TurtleUpdate) -> None:
        t = update.turtle
        try:
            self.pose_pub.publish(t.x, t.y, t.theta, t.linear_velocity, t.w)
            if update.colour is not None:
                self.colour_pub.publish(*update.colour)
        except Exception as err:  # noqa: BLE001  (e.g. a value that cannot be packed: never stop the tick)
            rospy.logerr_throttle(1.0, "%s: could not publish the pose: %r" % (self.name, err))

    def shutdown(self) -> None:
        self.pose_pub.unregister()
        self.colour_pub.unregister()
        self.cmd_sub.unregister()
        for service in self.services:
            service.shutdown("turtle killed")

    def _on_cmd_vel(self, msg: Twist) -> None:
        now = time.monotonic()
        try:
            clamped = self._sim.with_turtle(self.name, lambda t: t.command(msg.linear.x, msg.linear.y,
                                                                           msg.angular.z, now))
        except (ValueError, TurtleError) as err:  # non-finite: dropped
            rospy.logwarn_throttle(1.0, "%s: %s" % (self.name, err))
            return
        if clamped:
            rospy.logwarn_throttle(1.0, "%s: %s" % (self.name, clamped))

    def _on_set_pen(self, req):
        self._sim.call(self.name, lambda t: t.set_pen(req.r, req.g, req.b, req.width, req.off))
        return SetPenResponse()

    def _on_teleport_absolute(self, req):
        self._sim.call(self.name, lambda t: t.teleport_absolute(req.x, req.y, req.theta))
        return TeleportAbsoluteResponse()

    def _on_teleport_relative(self, req):
        self._sim.call(self.name, lambda t: t.teleport_relative(req.linear, req.angular))
        return TeleportRelativeResponse()


class TurtlesimNode:
    """The simulator process: frame, ROS interfaces, the 62.5 Hz ticker and the image outputs."""

    def __init__(self) -> None:
        self.lock = threading.RLock()
        params = private_params()  # one master round trip for all of them: start-up time counts
        for param, value in zip(BACKGROUND_PARAMS, DEFAULT_BACKGROUND_RGB):
            if param not in params:
                rospy.set_param("~" + param, value)
                params[param] = value
        self.frame = TurtleFrame(Canvas(background_from(params)), canonical=rospy.resolve_name)
        self.interfaces: Dict[str, TurtleInterface] = {}
        self.image_pub = rospy.Publisher("~image", Image, queue_size=1)
        self.image_period = 1.0 / max(float(params.get("image_rate", 10.0)), 0.1)
        self.frames = FrameGate()
        self.changes = 0  # counts what changed the picture (a move, a line, a clear, a spawn, a kill)
        self._last_poses: list = []
        self.scene = SceneLog()
        self.scene_pub = rospy.Publisher("~scene", String, queue_size=SCENE_QUEUE)
        self._ticks = 0
        # ~scene records lines while someone subscribes, and for a while after a ~canvas call: the
        # page asks ~canvas while its subscriber still connects, and must get the lines in between.
        self._scene_asked_until = 0.0
        self.snapshot_dir = os.path.expanduser(params.get(
            "snapshot_dir", os.path.join(os.environ.get("ROS_HOME", "~/.ros"), "turtlesim")))
        self._snapshots = 0
        self._services = [
            rospy.Service("clear", Empty, self._on_clear),
            rospy.Service("reset", Empty, self._on_reset),
            rospy.Service("spawn", Spawn, self._on_spawn),
            rospy.Service("kill", Kill, self._on_kill),
            rospy.Service("~snapshot", Trigger, self._on_snapshot),
            rospy.Service("~canvas", Trigger, self._on_canvas),
        ]
        self._add_turtle("", CENTRE, CENTRE, 0.0)
        self.ticker = Ticker(TICK, self.tick, name="turtlesim-tick", on_error=self._on_tick_error,
                             batch=self._ticks_per_wake)
        self.image_thread = threading.Thread(target=self._stream_images, name="turtlesim-image", daemon=True)

    def start(self) -> None:
        self.ticker.start()
        self.image_thread.start()

    def stop(self) -> None:
        self.ticker.stop()

    # -- helpers used by the turtle interfaces ------------------------------------------
    def with_turtle(self, name: str, action):
        """action(turtle) under the lock, and what it returns."""
        with self.lock:
            turtle = self.frame.turtles.get(name)
            if turtle is None:
                raise TurtleError("turtle [%s] does not exist" % name)
            return action(turtle)

    def call(self, name: str, action) -> None:
        """Run a service action on a turtle; refusals become failed calls with the reason."""
        try:
            self.with_turtle(name, action)
        except (ValueError, TurtleError) as err:
            rospy.logerr(str(err))
            raise rospy.ServiceException(str(err))

    @staticmethod
    def background() -> RGB:
        """The background_r/g/b params as they are now."""
        return background_from(private_params())

    # -- the heartbeat --------------------------------------------------------------------
    def tick(self) -> None:
        with self.lock:
            updates = self.frame.update(TICK, time.monotonic(), self._colour_wanted)
            targets = [(self.interfaces.get(u.name), u) for u in updates]
            self._ticks += 1
            scene = self._follow(updates)
        if scene is not None:
            self.scene_pub.publish(String(scene))
        for iface, update in targets:
            if update.error is not None:
                rospy.logerr_throttle(1.0, "turtle [%s] stopped: its update failed: %r" % (update.name, update.error))
            if update.result.clamped_from is not None:
                rospy.logwarn(WALL_WARNING % update.result.clamped_from)
            if iface is not None:
                iface.publish(update)

    def _follow(self, updates) -> Optional[str]:
        """What ~image and ~scene need from one tick (under the lock): whether the picture changed,
        the lines and poses for ~scene, and the ~scene update due now (or None). Nothing at all
        while nobody watches: a still turtlesim nobody looks at does no more than upstream's."""
        image_impl = self.image_pub.impl
        image_watched = image_impl is not None and bool(image_impl.connections)
        scene_watched = self.scene_pub.get_num_connections() > 0 or time.monotonic() < self._scene_asked_until
        if not (image_watched or scene_watched):
            return None
        poses = [(u.name, u.turtle.x, u.turtle.y, u.turtle.theta, u.turtle.icon) for u in updates]
        if image_watched and (poses != self._last_poses
                              or any(u.result.segments and u.turtle.pen.on for u in updates)):
            self.changes += 1
            self._last_poses = poses
        if not scene_watched:
            return None
        self.scene.record(((u.turtle.pen, u.result.segments) for u in updates),
                          [pose + (u.turtle.vx, u.turtle.vy, u.turtle.w) for pose, u in zip(poses, updates)])
        return self.scene.take() if self.scene.due() else None

    def _ticks_per_wake(self) -> int:
        """Ticks at each wake-up of the heartbeat: one while anyone takes a pose or a colour sensor
        (they see every tick, 62.5 a second, as upstream's); UNHEARD_TICKS_PER_WAKE while nobody
        does, when only the motion, the canvas and ~scene follow the ticks."""
        heard = any(iface.listened_to() for iface in list(self.interfaces.values()))
        return 1 if heard else UNHEARD_TICKS_PER_WAKE

    def _colour_wanted(self, name: str) -> bool:
        iface = self.interfaces.get(name)
        return iface is not None and iface.wants_colour()

    @staticmethod
    def _on_tick_error(err: Exception) -> None:
        rospy.logerr_throttle(1.0, "turtlesim tick failed (the simulation goes on): %r" % err)

    def render(self):
        with self.lock:
            return self.frame.render()

    def _stream_images(self) -> None:
        while not rospy.is_shutdown():
            started = time.monotonic()
            impl = self.image_pub.impl
            subscribers = frozenset(id(c) for c in impl.connections) if impl is not None else frozenset()
            if self.frames.due(subscribers, self.changes):
                image = self.render()
                msg = Image(height=image.height(), width=image.width(), encoding="rgb8",
                            is_bigendian=0, step=image.width() * 3, data=rgb888_bytes(image))
                msg.header.stamp = rospy.Time.now()
                msg.header.frame_id = "turtlesim"
                try:
                    self.image_pub.publish(msg)
                except rospy.ROSException:
                    return
            time.sleep(max(0.0, self.image_period - (time.monotonic() - started)))

    # -- turtles ---------------------------------------------------------------------------
    def _add_turtle(self, name: str, x: float, y: float, theta: float) -> str:
        with self.lock:
            real_name = self.frame.spawn(name, x, y, theta)
        self._attach(real_name)
        return real_name

    def _attach(self, name: str) -> None:
        """Give a freshly spawned turtle its topics and services."""
        with self.lock:
            t = self.frame.turtles.get(name)
        if t is None:
            return
        rospy.loginfo("Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]" % (name, t.x, t.y, t.theta))
        with self.lock:
            if name in self.interfaces:
                return  # kept across a reset
        iface = TurtleInterface(name, self)
        with self.lock:
            if self.frame.has(name) and name not in self.interfaces:
                self.interfaces[name] = iface
                return
        iface.shutdown()

    # -- global services -------------------------------------------------------------------
    def _on_spawn(self, req):
        try:
            return SpawnResponse(self._add_turtle(req.name, req.x, req.y, req.theta))
        except TurtleError as err:
            rospy.logerr(str(err))
            raise rospy.ServiceException(str(err))

    def _on_kill(self, req):
        try:
            with self.lock:
                self.frame.kill(req.name)
                iface = self.interfaces.pop(req.name, None)
        except TurtleError as err:
            rospy.logerr(str(err))
            raise rospy.ServiceException(str(err))
        if iface is not None:
            iface.shutdown()
        return KillResponse()

    def _on_clear(self, _req):
        rospy.loginfo("Clearing turtlesim.")
        background = self.background()
        with self.lock:
            self.frame.clear(background)
            self.scene.clear(background)
            self.changes += 1
        return EmptyResponse()

    def _on_reset(self, _req):
        rospy.loginfo("Resetting turtlesim.")
        background = self.background()
        with self.lock:
            removed, first = self.frame.reset(background)
            self.scene.clear(background)
            self.changes += 1
            # The new turtle1 keeps the old one's topics and services. Re-advertising them makes
            # every /turtle1/pose subscriber reconnect, and rospy can lose that race (the master's
            # "no publisher" and "publisher back" updates may arrive in either order), leaving a
            # node that called /reset deaf to the pose it needs next.
            dropped = [self.interfaces.pop(n) for n in removed if n in self.interfaces and n != first]
        for iface in dropped:
            iface.shutdown()
        self._attach(first)
        return EmptyResponse()

    def _on_canvas(self, _req):
        with self.lock:
            self._scene_asked_until = time.monotonic() + SCENE_GRACE_S
            paths = self.frame.canvas.path.copy()
            state = self.scene.state()
            icons = [self.frame.canvas.icons.image(i) for i in range(len(self.frame.canvas.icons))]
        return TriggerResponse(success=True, message=snapshot_json(state, paths, icons))

    def _on_snapshot(self, _req):
        try:
            os.makedirs(self.snapshot_dir, exist_ok=True)
            self._snapshots += 1
            path = os.path.join(self.snapshot_dir, "turtlesim-%s-%d-%03d.png"
                                % (time.strftime("%Y%m%d-%H%M%S"), os.getpid(), self._snapshots))
            if not self.render().save(path, "PNG"):
                return TriggerResponse(success=False, message="could not write %s" % path)
            return TriggerResponse(success=True, message=os.path.abspath(path))
        except OSError as err:
            return TriggerResponse(success=False, message="snapshot failed: %s" % err)
