"""The free camera's ROS side (gzclient's user camera, for clients without a display), under the
`gazebo` node's namespace:
- `~free_camera/image_raw` (sensor_msgs/Image, rgb8): rendered only while subscribed, at
  `~free_camera/rate` Hz of wall time (default 20; it also renders while physics is paused),
  `~free_camera/width` x `~free_camera/height` (default 480x360), stamped with sim time;
- `~free_camera/set_view`: a topic (gazebo_msgs/OrbitView, for mouse drags: latest wins) and a
  service (gazebo_msgs/SetOrbitView, answers the view applied or why not);
- `~free_camera/view` (gazebo_msgs/OrbitView, latched): the view in force, after clamping.
Rendering runs in a thread of its own: the world's lock is held only to copy the scene (well
under a millisecond), rasterising happens outside it, so the physics keeps its pace."""
from __future__ import annotations

import math
import threading
import time
from dataclasses import replace
from typing import Optional

import rospy
from gazebo_msgs.msg import OrbitView as OrbitViewMsg
from gazebo_msgs.srv import SetOrbitView, SetOrbitViewResponse
from geometry_msgs.msg import Point
from sensor_msgs.msg import Image
from std_msgs.msg import Header

from ..engine.camera import RenderUnavailable
from ..engine.free_camera import DEFAULT_VIEW, FREE_CAMERA_CONFIG, FreeCamera, OrbitView, ViewError, checked_view
from ..engine.world import World
from .conversions import stamp_from_sim

FRAME_ID = "free_camera"
MAX_SIZE = 4096  # pixels a side: more is a typo, and each picture would take over 50 MB
DEFAULT_RATE_HZ = 20.0  # wall time: a browser wants a smooth picture even when the physics is paused


def view_from_msg(msg: OrbitViewMsg) -> OrbitView:
    """ViewError for non-finite values; others clamped (engine.free_camera.checked_view)."""
    return checked_view((msg.target.x, msg.target.y, msg.target.z), msg.azimuth, msg.elevation, msg.distance)


def view_to_msg(view: OrbitView) -> OrbitViewMsg:
    return OrbitViewMsg(target=Point(*view.target), azimuth=view.azimuth, elevation=view.elevation,
                        distance=view.distance)


class FreeCameraPublisher:
    """Publishes the free camera's pictures of `world` while someone watches."""

    def __init__(self, world: World, lock: threading.Lock) -> None:
        self.world, self.lock = world, lock
        try:
            rate = float(rospy.get_param("~free_camera/rate", DEFAULT_RATE_HZ))
            if not (math.isfinite(rate) and 0.0 < rate <= 1000.0):
                raise ValueError("rate must be in (0, 1000] Hz, got %r" % rate)
            width = int(rospy.get_param("~free_camera/width", FREE_CAMERA_CONFIG.width))
            height = int(rospy.get_param("~free_camera/height", FREE_CAMERA_CONFIG.height))
            if not (0 < width <= MAX_SIZE and 0 < height <= MAX_SIZE):
                raise ValueError("size must be within 1..%d pixels, got %dx%d" % (MAX_SIZE, width, height))
            config = replace(FREE_CAMERA_CONFIG, width=width, height=height)
        except (TypeError, ValueError) as exc:
            rate, config = DEFAULT_RATE_HZ, FREE_CAMERA_CONFIG
            rospy.logwarn("free camera: %s; using %dx%d at %g Hz" % (exc, config.width, config.height, rate))
        self.period = 1.0 / rate
        self.camera = FreeCamera(config, DEFAULT_VIEW)
        self._stop = threading.Event()
        self._view_lock = threading.Lock()  # the latched view is the one in force, whoever sets it
        self._thread: Optional[threading.Thread] = None
        self.image_pub = rospy.Publisher("~free_camera/image_raw", Image, queue_size=1)
        self.view_pub = rospy.Publisher("~free_camera/view", OrbitViewMsg, queue_size=1, latch=True)
        self.view_pub.publish(view_to_msg(self.camera.view))
        rospy.Subscriber("~free_camera/set_view", OrbitViewMsg, self._set_view_topic, queue_size=1)
        rospy.Service("~free_camera/set_view", SetOrbitView, self._set_view_service)

    # ---- the view ---------------------------------------------------------------------
    def _apply(self, msg: OrbitViewMsg) -> OrbitView:
        view = view_from_msg(msg)
        with self._view_lock:
            self.camera.view = view
            self.view_pub.publish(view_to_msg(view))
        return view

    def _set_view_topic(self, msg: OrbitViewMsg) -> None:
        try:
            self._apply(msg)
        except ViewError as exc:
            rospy.logwarn_throttle(1.0, "free_camera/set_view topic: refused: %s" % exc)

    def _set_view_service(self, req) -> SetOrbitViewResponse:
        try:
            view = self._apply(req.view)
        except ViewError as exc:
            return SetOrbitViewResponse(view_to_msg(self.camera.view), False, "SetOrbitView: refused: %s" % exc)
        return SetOrbitViewResponse(view_to_msg(view), True, "SetOrbitView: view set")

    # ---- rendering --------------------------------------------------------------------
    def start(self) -> None:
        self._thread = threading.Thread(target=self._run, name="free_camera", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5.0)
        self.camera.close()

    def _run(self) -> None:
        try:
            self._loop()
        except rospy.ROSException:
            if not rospy.core.is_shutdown_requested():
                raise
            # shutting down: rospy closed the topic between the loop's check and its publish

    def _loop(self) -> None:
        due = time.monotonic()
        while not self._stop.is_set() and not rospy.core.is_shutdown_requested():
            if self.image_pub.get_num_connections() == 0:
                self._stop.wait(0.05)
                due = time.monotonic()
                continue
            if not self._publish_frame():
                return
            due = max(due + self.period, time.monotonic())  # behind: skip frames, no burst
            self._stop.wait(due - time.monotonic())

    def _publish_frame(self) -> bool:
        """One picture; False when rendering is impossible (then the thread ends)."""
        try:
            self.world.prepare(self.camera)  # GL set-up for a new model: outside the lock
            with self.lock:
                stamp = stamp_from_sim(self.world.time)
                self.world.capture(self.camera)
            pixels = self.camera.draw()
        except RenderUnavailable as exc:
            rospy.logwarn("free camera not rendered: %s; %s stays silent" % (exc, self.image_pub.resolved_name))
            return False
        except Exception as exc:  # a GL/MuJoCo failure must not take the node down
            rospy.logerr_throttle(5.0, "free camera: render failed: %s" % exc)
            return True
        height, width = pixels.shape[:2]
        self.image_pub.publish(Image(header=Header(stamp=stamp, frame_id=FRAME_ID), height=height, width=width,
                                     encoding="rgb8", is_bigendian=0, step=width * 3, data=pixels.tobytes()))
        return True
