"""The `gazebo` node: Gazebo's ROS API (topics and services of gazebo_ros_api_plugin) over
a World. It owns the stepping loop (fixed step, paced to a real-time factor, /clock), and
wires services/topics to World calls under one lock. Logic lives in World and the plugins."""
from __future__ import annotations

import os
import threading
import time
from typing import Callable, Dict, List, Optional

import mujoco
import rospy
from gazebo_msgs.msg import LinkStates, ModelState, ModelStates
from gazebo_msgs.srv import (DeleteModel, DeleteModelResponse, GetLinkState, GetLinkStateResponse, GetModelState,
                             GetModelStateResponse, GetWorldProperties, GetWorldPropertiesResponse, SetModelState,
                             SetModelStateResponse, SpawnModel, SpawnModelResponse)
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty, EmptyResponse

from ..engine import database
from ..engine.frames import Pose, twist_relative
from ..engine.pacing import Pacer
from ..engine.sdf import SdfError, WorldFile
from ..engine.window import SimulatorWindow, WindowUnavailable
from ..engine.world import World, WorldError
from ..plugins import Plugin, make_plugins
from .conversions import (pose_from_msg, pose_msg_problem, pose_to_msg, stamp_from_sim, twist_from_msg,
                          twist_msg_problem, twist_to_msg)
from .free_camera import FreeCameraPublisher


class GazeboServer:
    def __init__(self, world_desc: Optional[WorldFile] = None, real_time_factor: float = 1.0, paused: bool = False,
                 states_rate: float = 100.0, steps_per_update: int = 5, gui: bool = False) -> None:
        """`world_desc`: the parsed world file (physics settings and included models), if any."""
        # MuJoCo's warnings go to the node's log (not stdout and ./MUJOCO_LOG.TXT)
        mujoco.set_mju_user_warning(lambda text: rospy.logwarn_throttle(5.0, "MuJoCo: %s" % text.strip()))
        step, gravity = 0.001, (0.0, 0.0, -9.81)
        if world_desc is not None:
            step = world_desc.max_step_size or step
            if world_desc.gravity is not None:
                gravity = tuple(world_desc.gravity)
        self.world = World(timestep=step, gravity=gravity)
        self.world.paused = paused
        self.lock = threading.Lock()
        self.plugins: Dict[str, List[Plugin]] = {}
        self.rtf = real_time_factor
        self.steps_per_update = max(1, int(steps_per_update))
        self.states_period = 1.0 / states_rate if states_rate > 0 else 0.0
        self._next_states = 0.0
        if world_desc is not None:
            self._load_world_models(world_desc)
        # Every attribute a callback reads is set before the first topic or service goes up: a
        # spawn request can arrive the moment its service is advertised.
        self.viewer = self._open_viewer() if gui else None
        self.free_camera = FreeCameraPublisher(self.world, self.lock)
        self.clock_pub = rospy.Publisher("/clock", Clock, queue_size=10)
        self.model_states_pub = rospy.Publisher("~model_states", ModelStates, queue_size=1)
        self.link_states_pub = rospy.Publisher("~link_states", LinkStates, queue_size=1)
        rospy.Subscriber("~set_model_state", ModelState, self._set_model_state_topic, queue_size=10)
        rospy.Service("~spawn_urdf_model", SpawnModel, self._spawn)
        rospy.Service("~spawn_sdf_model", SpawnModel, self._spawn)
        rospy.Service("~delete_model", DeleteModel, self._delete)
        rospy.Service("~get_model_state", GetModelState, self._get_model_state)
        rospy.Service("~set_model_state", SetModelState, self._set_model_state)
        rospy.Service("~get_link_state", GetLinkState, self._get_link_state)
        rospy.Service("~get_world_properties", GetWorldProperties, self._world_properties)
        rospy.Service("~pause_physics", Empty, self._pause)
        rospy.Service("~unpause_physics", Empty, self._unpause)
        rospy.Service("~reset_world", Empty, self._reset_world)
        rospy.Service("~reset_simulation", Empty, self._reset_simulation)

    def _load_world_models(self, desc: WorldFile) -> None:
        for inc in desc.includes:
            try:
                sdf = inc.inline_sdf or database.resolve_uri(inc.uri)
                if "<link" not in sdf:
                    continue  # lights (model://sun) have no bodies
                name = inc.name or inc.uri.split("/")[-1]
                self.world.spawn(name, sdf, inc.pose or Pose())
            except (database.DatabaseError, WorldError, SdfError) as exc:
                rospy.logwarn("world file: skipping %s: %s" % (inc.uri or inc.name, exc))

    def _open_viewer(self) -> Optional[SimulatorWindow]:
        """The simulator window (gui:=true), or None with one warning saying why (headless)."""
        window = SimulatorWindow()
        try:
            window.open(self.world.model, self.world.data, os.environ)
        except WindowUnavailable as exc:
            rospy.logwarn("gui: no simulator window (%s); running headless" % exc)
            return None
        return window

    # ---- services ---------------------------------------------------------------------
    def _spawn(self, req) -> SpawnModelResponse:
        problem = pose_msg_problem(req.initial_pose)
        if problem:
            return SpawnModelResponse(False, "SpawnModel: Failure - initial_pose of [%s]: %s" % (req.model_name, problem))
        with self.lock:
            try:
                ref_pose, _ = self.world.frame_state(req.reference_frame)
                pose = ref_pose.compose(pose_from_msg(req.initial_pose))
                entry = self.world.spawn(req.model_name, req.model_xml, pose, req.robot_namespace)
                self._reopen_viewer()
                self.plugins[entry.name] = make_plugins(entry, self.lock, self.world)
            except WorldError as exc:
                return SpawnModelResponse(False, "SpawnModel: Failure - %s" % exc)
        rospy.loginfo("spawned model [%s]" % req.model_name)
        return SpawnModelResponse(True, "SpawnModel: Successfully spawned entity")

    def _reopen_viewer(self) -> None:
        """After spawn/delete (the caller holds the lock): the window shows the new model."""
        if self.viewer is None:
            return
        try:
            self.viewer.reopen(self.world.model, self.world.data, os.environ)
        except WindowUnavailable as exc:
            rospy.logwarn("gui: simulator window lost (%s); running headless" % exc)
            self.viewer = None

    def _delete(self, req) -> DeleteModelResponse:
        with self.lock:
            try:
                self.world.delete(req.model_name)
            except WorldError as exc:
                return DeleteModelResponse(False, "DeleteModel: %s" % exc)
            for plugin in self.plugins.pop(req.model_name, []):
                plugin.close()
            self._reopen_viewer()
        return DeleteModelResponse(True, "DeleteModel: successfully deleted model")

    def _get_model_state(self, req) -> GetModelStateResponse:
        res = GetModelStateResponse()
        with self.lock:
            try:
                pose, twist = self.world.get_model_state(req.model_name, req.relative_entity_name)
            except WorldError as exc:
                res.success, res.status_message = False, "GetModelState: %s" % exc
                return res
            res.header.stamp = stamp_from_sim(self.world.time)
        res.header.frame_id = req.relative_entity_name
        res.pose, res.twist = pose_to_msg(pose), twist_to_msg(twist)
        res.success, res.status_message = True, "GetModelState: got properties"
        return res

    def _get_link_state(self, req) -> GetLinkStateResponse:
        res = GetLinkStateResponse()
        with self.lock:
            try:
                bid = self.world.entity_body(req.link_name)
                ref_pose, ref_twist = self.world.frame_state(req.reference_frame)
                pose = self.world.body_pose(bid).relative_to(ref_pose)
                twist = twist_relative(self.world.body_twist(bid), ref_twist, ref_pose)
            except WorldError as exc:
                res.success, res.status_message = False, "GetLinkState: %s" % exc
                return res
        res.link_state.link_name, res.link_state.reference_frame = req.link_name, req.reference_frame
        res.link_state.pose, res.link_state.twist = pose_to_msg(pose), twist_to_msg(twist)
        res.success, res.status_message = True, "GetLinkState: got state"
        return res

    def _apply_model_state(self, state: ModelState) -> str:
        """'' on success, else the reason."""
        problem = pose_msg_problem(state.pose) or twist_msg_problem(state.twist)
        if problem:
            return "refused state of [%s]: %s" % (state.model_name, problem)
        with self.lock:
            try:
                self.world.set_model_state(state.model_name, pose_from_msg(state.pose), twist_from_msg(state.twist),
                                           state.reference_frame)
            except WorldError as exc:
                return str(exc)
        return ""

    def _set_model_state(self, req) -> SetModelStateResponse:
        error = self._apply_model_state(req.model_state)
        if error:
            return SetModelStateResponse(False, "SetModelState: %s" % error)
        return SetModelStateResponse(True, "SetModelState: set model state done")

    def _set_model_state_topic(self, msg: ModelState) -> None:
        error = self._apply_model_state(msg)
        if error:
            rospy.logwarn_throttle(1.0, "set_model_state topic: %s" % error)

    def _world_properties(self, _req) -> GetWorldPropertiesResponse:
        with self.lock:
            return GetWorldPropertiesResponse(sim_time=self.world.time, model_names=list(self.world.models),
                                              rendering_enabled=self.viewer is not None, success=True,
                                              status_message="GetWorldProperties: got properties")

    def _pause(self, _req) -> EmptyResponse:
        with self.lock:
            self.world.paused = True
        return EmptyResponse()

    def _unpause(self, _req) -> EmptyResponse:
        with self.lock:
            self.world.paused = False
        return EmptyResponse()

    def _reset(self, full: bool) -> EmptyResponse:
        with self.lock:
            self.world.reset_simulation() if full else self.world.reset_world()
            for plugins in self.plugins.values():
                for plugin in plugins:
                    plugin.reset(self.world)
            self._next_states = 0.0
            self._rebase = True
        return EmptyResponse()

    def _reset_world(self, _req) -> EmptyResponse:
        return self._reset(False)

    def _reset_simulation(self, _req) -> EmptyResponse:
        return self._reset(True)

    # ---- the loop ---------------------------------------------------------------------
    def _publish_states(self, now: float) -> None:
        if self.model_states_pub.get_num_connections() > 0:
            names, poses, twists = self.world.model_states()
            self.model_states_pub.publish(ModelStates(name=names, pose=[pose_to_msg(p) for p in poses],
                                                      twist=[twist_to_msg(t) for t in twists]))
        if self.link_states_pub.get_num_connections() > 0:
            names, poses, twists = self.world.link_states()
            self.link_states_pub.publish(LinkStates(name=names, pose=[pose_to_msg(p) for p in poses],
                                                    twist=[twist_to_msg(t) for t in twists]))

    def run(self, wait: Callable[[], None]) -> None:
        """Step the world in a thread of its own until `wait` returns (rospy has shut down), then
        stop. Not in the main thread: Python runs signal handlers there, and one that shuts
        rospy down inside an interrupted publish (the loop publishes /clock at 200 Hz) waits for
        the lock that publish holds. The main thread only waits (see signals.py)."""
        physics = threading.Thread(target=self._physics, name="physics", daemon=True)
        physics.start()
        self.free_camera.start()
        wait()
        physics.join(timeout=5.0)
        self.free_camera.stop()
        if self.viewer is not None:
            self.viewer.close()

    def _physics(self) -> None:
        try:
            self._loop()
        except Exception as exc:  # a dead loop must not leave a node that answers but never steps
            if isinstance(exc, rospy.ROSException) and rospy.core.is_shutdown_requested():
                return  # shutting down: rospy closes topics before is_shutdown() turns true
            rospy.logfatal("gazebo: the simulation loop failed: %r" % exc)
            rospy.signal_shutdown("simulation loop failed")
            raise

    def _loop(self) -> None:
        pacer = Pacer(self.rtf, time.monotonic(), self.world.time)
        self._rebase = False
        last_view = 0.0
        while not rospy.core.is_shutdown_requested():
            with self.lock:
                paused = self.world.paused
                if not paused:
                    divergences = self.world.divergences
                    self.world.step(self.steps_per_update)
                    if self.world.divergences != divergences:
                        rospy.logwarn_throttle(1.0, "t=%.3f s: %s" % (self.world.time, self.world.last_divergence))
                now = self.world.time
                if self._rebase:
                    pacer.rebase(time.monotonic(), now)
                    self._rebase = False
                self.clock_pub.publish(Clock(stamp_from_sim(now)))
                if not paused:
                    if now + 1e-9 >= self._next_states:
                        self._next_states = max(self._next_states + self.states_period, now - self.states_period)
                        self._publish_states(now)
                    for plugins in self.plugins.values():
                        for plugin in plugins:
                            if plugin.due(now):
                                plugin.update(self.world, now)
                if self.viewer is not None and time.monotonic() - last_view > 1 / 30:
                    last_view = time.monotonic()
                    self.viewer.sync()
            if paused:
                time.sleep(0.01)
                pacer.rebase(time.monotonic(), now)
                continue
            delay = pacer.delay(time.monotonic(), now)
            if delay > 0:
                time.sleep(delay)
