"""The simulated world: a MuJoCo model built from an editable mujoco.MjSpec, with a
registry of named models (Gazebo's notion), spawn/delete at run time that keep the
state of everything else (edit the spec, recompile, copy qpos/qvel by joint name), and
Gazebo-style model/link state queries and edits in any reference frame."""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import mujoco
import numpy as np

from .frames import Pose, Twist, all_finite, quat_conj, rotate, twist_relative, twist_to_world
from .sdf import SdfError, sdf_to_mjcf
from .appearance import urdf_link_colours
from .urdf import PluginSpec, UrdfError, inspect_urdf

WORLD_FRAMES = ("", "world", "map")
_NAME_RE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.\-]*$")
_QPOS_SIZE = {int(mujoco.mjtJoint.mjJNT_FREE): 7, int(mujoco.mjtJoint.mjJNT_BALL): 4,
              int(mujoco.mjtJoint.mjJNT_SLIDE): 1, int(mujoco.mjtJoint.mjJNT_HINGE): 1}
_QVEL_SIZE = {int(mujoco.mjtJoint.mjJNT_FREE): 6, int(mujoco.mjtJoint.mjJNT_BALL): 3,
              int(mujoco.mjtJoint.mjJNT_SLIDE): 1, int(mujoco.mjtJoint.mjJNT_HINGE): 1}


class WorldError(ValueError):
    """A request the world refuses; the message is what the ROS caller sees."""


@dataclass
class ModelEntry:
    """One named model in the world."""

    name: str
    fmt: str                      # "urdf" or "sdf"
    fixed: bool                   # no free joint: welded to the world (static SDF, URDF with a `world` link)
    root_body: str                # full MuJoCo body name, "<model>::<link>"
    spawn_pose: Pose              # model pose at spawn (for reset_world)
    body_local: Pose              # root body pose in the model frame
    frame: object = None          # MjsFrame holding the model in the spec
    body: object = None           # MjsBody (root) in the spec
    joints: List[str] = field(default_factory=list)     # actuated joint names (unscoped)
    plugins: List[PluginSpec] = field(default_factory=list)
    robot_namespace: str = ""


def detect_format(xml: str) -> str:
    """'urdf' when the root element is <robot>, 'sdf' for <sdf>/<model>; else a WorldError."""
    head = re.sub(r"<\?xml.*?\?>|<!--.*?-->", "", xml, flags=re.S).lstrip()
    if head.startswith("<robot"):
        return "urdf"
    if head.startswith("<sdf") or head.startswith("<model"):
        return "sdf"
    raise WorldError("model_xml is neither URDF (<robot>) nor SDF (<sdf>)")


class World:
    """MuJoCo world with Gazebo's model registry semantics. Not thread-safe: callers lock."""

    def __init__(self, timestep: float = 0.001, gravity: Tuple[float, float, float] = (0.0, 0.0, -9.81)) -> None:
        self.spec = mujoco.MjSpec()
        self.spec.option.timestep = timestep
        self.spec.option.gravity = list(gravity)
        # implicit in velocity: stiff wheel velocity servos on light wheels stay stable at 1 ms
        self.spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
        self.spec.compiler.fusestatic = False
        self.spec.compiler.discardvisual = True
        self.spec.visual.global_.offwidth = 640
        self.spec.visual.global_.offheight = 480
        self.spec.worldbody.add_light(pos=[0, 0, 10], dir=[0, 0, -1], type=mujoco.mjtLightType.mjLIGHT_DIRECTIONAL)
        self.models: Dict[str, ModelEntry] = {}
        self._actuation: Dict[str, Tuple[float, Tuple[float, float, float], float, Optional[float]]] = {}
        self.model: mujoco.MjModel = self.spec.compile()
        self.data = mujoco.MjData(self.model)
        self.paused = False
        self._kinematics_stale = False

    # ---- time -------------------------------------------------------------------------
    @property
    def time(self) -> float:
        return float(self.data.time)

    @property
    def timestep(self) -> float:
        return float(self.model.opt.timestep)

    def step(self, n: int = 1) -> None:
        mujoco.mj_step(self.model, self.data, nstep=n)
        # mj_step leaves body poses/velocities as they were *before* its last integration
        self._kinematics_stale = True

    def _refresh_kinematics(self) -> None:
        """Body poses and velocities of the current qpos/qvel (not one step behind), so a query
        answers the state that spawn/delete/set_model_state (which run mj_forward) keep. Cheap
        (no collision, no solver) and only when asked; the next mj_step recomputes all anyway."""
        if self._kinematics_stale:
            mujoco.mj_kinematics(self.model, self.data)
            mujoco.mj_comPos(self.model, self.data)
            mujoco.mj_comVel(self.model, self.data)
            self._kinematics_stale = False

    # ---- spawn / delete ----------------------------------------------------------------
    def spawn(self, name: str, xml: str, pose: Pose, robot_namespace: str = "") -> ModelEntry:
        """Add a model from URDF or SDF text at `pose` (world frame); the rest keeps its state."""
        if not name or not _NAME_RE.match(name):
            raise WorldError("invalid model name %r (letters, digits, _ . -)" % name)
        if name in self.models:
            raise WorldError("model name %s already exists in the world" % name)
        if not all_finite(pose.position, pose.orientation):
            raise WorldError("initial pose of %s is not finite" % name)
        fmt = detect_format(xml)
        plugins: List[PluginSpec] = []
        friction: Dict[str, float] = {}
        colours: Dict[str, Tuple[float, float, float, float]] = {}
        joints: List[str] = []
        try:
            if fmt == "urdf":
                info = inspect_urdf(xml)
                child = mujoco.MjSpec.from_string(xml)
                fixed, plugins, friction = info.fixed_to_world, info.plugins, info.friction
                colours = urdf_link_colours(xml)  # cosmetic: what the camera sees
                joints = [j for j, t in info.joints.items() if t in ("revolute", "continuous", "prismatic")]
                model_offset = Pose()
            else:
                converted = sdf_to_mjcf(xml)
                child = mujoco.MjSpec.from_string(converted.mjcf)
                fixed, model_offset = converted.static, converted.pose
        except (UrdfError, SdfError) as exc:
            raise WorldError(str(exc)) from exc
        except Exception as exc:  # MuJoCo's parser: mujoco.FatalError / ValueError
            raise WorldError("MuJoCo cannot load the %s: %s" % (fmt.upper(), exc)) from exc
        root = child.worldbody.first_body()
        if root is None:
            raise WorldError("model %s has no bodies" % name)
        for body in child.bodies:
            if body.name in colours:
                for geom in body.geoms:
                    geom.rgba = list(colours[body.name])
            if body.name in friction:
                for geom in body.geoms:
                    geom.friction = [friction[body.name], geom.friction[1], geom.friction[2]]
        body_local = Pose(np.array(root.pos), np.array(root.quat))
        frame_pose = pose.compose(model_offset)
        world_body_pose = frame_pose.compose(body_local)
        frame = self.spec.worldbody.add_frame()
        body = frame.attach_body(root, name + "::", "")
        body.pos, body.quat = world_body_pose.position, world_body_pose.orientation
        if not fixed:
            body.add_freejoint(name=name + "::__root__")
        for joint in joints:
            self.spec.add_actuator(name="%s::%s" % (name, joint), target="%s::%s" % (name, joint),
                                   trntype=mujoco.mjtTrn.mjTRN_JOINT, biastype=mujoco.mjtBias.mjBIAS_AFFINE,
                                   gainprm=[0.0] * 10)  # passive until a controller commands it
        entry = ModelEntry(name=name, fmt=fmt, fixed=fixed, root_body=body.name,
                           spawn_pose=world_body_pose, body_local=body_local, frame=frame,
                           body=body, joints=joints, plugins=plugins, robot_namespace=robot_namespace)
        self.models[name] = entry
        try:
            self._recompile()
        except Exception as exc:
            self._remove_from_spec(entry)
            del self.models[name]
            raise WorldError("MuJoCo cannot compile model %s: %s" % (name, exc)) from exc
        return entry

    def delete(self, name: str) -> None:
        entry = self.models.get(name)
        if entry is None:
            raise WorldError("model [%s] does not exist" % name)
        self._remove_from_spec(entry)
        del self.models[name]
        for key in [k for k in self._actuation if k.startswith(name + "::")]:
            del self._actuation[key]
        self._recompile()

    def _remove_from_spec(self, entry: ModelEntry) -> None:
        for act in list(self.spec.actuators):
            if act.name.startswith(entry.name + "::"):
                self.spec.delete(act)
        self.spec.delete(entry.body)  # the (empty) frame stays: deleting frames is not safe in MjSpec

    def _recompile(self) -> None:
        """Compile the edited spec and carry every surviving joint's qpos/qvel and the time over."""
        old_m, old_d = self.model, self.data
        new_m = self.spec.compile()
        new_d = mujoco.MjData(new_m)
        for j in range(new_m.njnt):
            jname = new_m.joint(j).name
            if not jname:
                continue
            oid = mujoco.mj_name2id(old_m, mujoco.mjtObj.mjOBJ_JOINT, jname)
            if oid < 0 or old_m.jnt_type[oid] != new_m.jnt_type[j]:
                continue
            nq, nv = _QPOS_SIZE[int(new_m.jnt_type[j])], _QVEL_SIZE[int(new_m.jnt_type[j])]
            new_d.qpos[new_m.jnt_qposadr[j]:new_m.jnt_qposadr[j] + nq] = \
                old_d.qpos[old_m.jnt_qposadr[oid]:old_m.jnt_qposadr[oid] + nq]
            new_d.qvel[new_m.jnt_dofadr[j]:new_m.jnt_dofadr[j] + nv] = \
                old_d.qvel[old_m.jnt_dofadr[oid]:old_m.jnt_dofadr[oid] + nv]
        new_d.time = old_d.time
        self.model, self.data = new_m, new_d
        self._apply_actuation()
        mujoco.mj_forward(self.model, self.data)

    # ---- actuation (joint controllers of the robot plugins) -----------------------------
    def _actuator_id(self, model: str, joint: str) -> int:
        aid = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_ACTUATOR, "%s::%s" % (model, joint))
        if aid < 0:
            raise WorldError("model %s has no actuated joint %s" % (model, joint))
        return aid

    def set_joint_effort(self, model: str, joint: str, effort: float) -> None:
        self._set_actuation(model, joint, 1.0, (0.0, 0.0, 0.0), effort, None)

    def set_joint_position(self, model: str, joint: str, target: float, kp: float, kd: float) -> None:
        """Position servo (PD on joint angle), as a ros_control position controller."""
        self._set_actuation(model, joint, kp, (0.0, -kp, -kd), target, None)

    def set_joint_velocity(self, model: str, joint: str, velocity: float, kv: float,
                           max_effort: Optional[float] = None) -> None:
        self._set_actuation(model, joint, kv, (0.0, 0.0, -kv), velocity, max_effort)

    def release_joint(self, model: str, joint: str) -> None:
        """No controller: the joint moves freely (zero actuator force)."""
        self._set_actuation(model, joint, 0.0, (0.0, 0.0, 0.0), 0.0, None)

    def _set_actuation(self, model: str, joint: str, gain: float, bias: Tuple[float, float, float],
                       ctrl: float, max_effort: Optional[float]) -> None:
        if not all_finite(np.array([gain, ctrl, *bias])):
            raise WorldError("non-finite command for %s::%s" % (model, joint))
        self._actuator_id(model, joint)
        self._actuation["%s::%s" % (model, joint)] = (gain, bias, ctrl, max_effort)
        self._apply_actuation()

    def _apply_actuation(self) -> None:
        for name, (gain, bias, ctrl, max_effort) in self._actuation.items():
            aid = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
            if aid < 0:
                continue
            self.model.actuator_gainprm[aid, 0] = gain
            self.model.actuator_biasprm[aid, :3] = bias
            self.model.actuator_forcelimited[aid] = max_effort is not None
            if max_effort is not None:
                self.model.actuator_forcerange[aid] = (-max_effort, max_effort)
            self.data.ctrl[aid] = ctrl

    # ---- queries ----------------------------------------------------------------------
    def _body_id(self, body: str) -> int:
        return mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, body)

    def body_pose(self, bid: int) -> Pose:
        self._refresh_kinematics()
        return Pose(self.data.xpos[bid].copy(), self.data.xquat[bid].copy())

    def body_twist(self, bid: int) -> Twist:
        """World-frame twist of a body's frame origin."""
        self._refresh_kinematics()
        vel = np.zeros(6)
        mujoco.mj_objectVelocity(self.model, self.data, mujoco.mjtObj.mjOBJ_BODY, bid, vel, 0)
        return Twist(vel[3:], vel[:3])

    def entry(self, name: str) -> ModelEntry:
        entry = self.models.get(name)
        if entry is None:
            raise WorldError("model [%s] does not exist" % name)
        return entry

    def entity_body(self, name: str) -> int:
        """Body id of a model (its canonical link) or of a scoped link 'model::link'."""
        if name in self.models:
            return self._body_id(self.models[name].root_body)
        bid = self._body_id(name) if "::" in name else -1
        if bid <= 0:
            raise WorldError("entity [%s] does not exist (not a model, not model::link)" % name)
        return bid

    def frame_state(self, ref: str) -> Tuple[Pose, Twist]:
        if ref in WORLD_FRAMES:
            return Pose(), Twist()
        bid = self.entity_body(ref)
        return self.body_pose(bid), self.body_twist(bid)

    def get_model_state(self, name: str, relative_entity: str = "") -> Tuple[Pose, Twist]:
        bid = self._body_id(self.entry(name).root_body)
        try:
            ref_pose, ref_twist = self.frame_state(relative_entity)
        except WorldError as exc:
            raise WorldError("reference entity [%s] not found: %s" % (relative_entity, exc)) from exc
        pose, twist = self.body_pose(bid), self.body_twist(bid)
        return pose.relative_to(ref_pose), twist_relative(twist, ref_twist, ref_pose)

    def set_model_state(self, name: str, pose: Pose, twist: Twist, reference_frame: str = "") -> None:
        """Teleport a model (pose and twist given in `reference_frame`), as Gazebo's service does."""
        entry = self.entry(name)
        if not all_finite(pose.position, pose.orientation, twist.linear, twist.angular):
            raise WorldError("pose/twist for [%s] is not finite" % name)
        try:
            ref_pose, _ = self.frame_state(reference_frame)
        except WorldError as exc:
            raise WorldError("reference frame [%s] not found: %s" % (reference_frame, exc)) from exc
        if self.entity_body(name) == (self.entity_body(reference_frame) if reference_frame not in WORLD_FRAMES else -1):
            raise WorldError("model [%s] cannot be set relative to itself" % name)
        world_pose = ref_pose.compose(pose)
        world_twist = twist_to_world(twist, ref_pose)
        self._place(entry, world_pose, world_twist)

    def _place(self, entry: ModelEntry, world_pose: Pose, world_twist: Twist) -> None:
        bid = self._body_id(entry.root_body)
        if entry.fixed:
            self.model.body_pos[bid] = world_pose.position
            self.model.body_quat[bid] = world_pose.orientation
            entry.body.pos, entry.body.quat = world_pose.position, world_pose.orientation
        else:
            jid = self.model.body_jntadr[bid]
            qa, va = self.model.jnt_qposadr[jid], self.model.jnt_dofadr[jid]
            self.data.qpos[qa:qa + 3] = world_pose.position
            self.data.qpos[qa + 3:qa + 7] = world_pose.orientation
            self.data.qvel[va:va + 3] = world_twist.linear
            self.data.qvel[va + 3:va + 6] = rotate(quat_conj(world_pose.orientation), world_twist.angular)
        mujoco.mj_forward(self.model, self.data)

    def model_states(self) -> Tuple[List[str], List[Pose], List[Twist]]:
        names, poses, twists = [], [], []
        for name, entry in self.models.items():
            bid = self._body_id(entry.root_body)
            names.append(name)
            poses.append(self.body_pose(bid))
            twists.append(self.body_twist(bid))
        return names, poses, twists

    def link_states(self) -> Tuple[List[str], List[Pose], List[Twist]]:
        names, poses, twists = [], [], []
        for bid in range(1, self.model.nbody):
            names.append(self.model.body(bid).name)
            poses.append(self.body_pose(bid))
            twists.append(self.body_twist(bid))
        return names, poses, twists

    def joint_states(self, model: str, joints: List[str]) -> Tuple[List[float], List[float], List[float]]:
        """Angle, rate and actuator effort of the named (unscoped) joints of a model."""
        pos, vel, eff = [], [], []
        for joint in joints:
            jid = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_JOINT, "%s::%s" % (model, joint))
            pos.append(float(self.data.qpos[self.model.jnt_qposadr[jid]]))
            vel.append(float(self.data.qvel[self.model.jnt_dofadr[jid]]))
            aid = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_ACTUATOR, "%s::%s" % (model, joint))
            eff.append(float(self.data.actuator_force[aid]) if aid >= 0 else 0.0)
        return pos, vel, eff

    # ---- resets -----------------------------------------------------------------------
    def reset_world(self) -> None:
        """Every model back to its spawn pose at rest; simulation time keeps running."""
        t = self.data.time
        mujoco.mj_resetData(self.model, self.data)
        for entry in self.models.values():
            if entry.fixed:
                self._place(entry, entry.spawn_pose, Twist())
        self.data.time = t
        self._apply_actuation()
        mujoco.mj_forward(self.model, self.data)

    def reset_simulation(self) -> None:
        self.reset_world()
        self.data.time = 0.0
