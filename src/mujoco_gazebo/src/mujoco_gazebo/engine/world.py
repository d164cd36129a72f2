"""The simulated world: a MuJoCo model built from an editable mujoco.MjSpec, with a
registry of named models (Gazebo's notion), spawn/delete at run time that keep the
state of everything else (edit the spec, recompile, copy qpos/qvel by joint name), and
Gazebo-style model/link state queries and edits in any reference frame.

Two guards keep it running for ever: requests outside what the physics can hold (limits.py)
are refused, and a step that diverges anyway (MuJoCo's instability check, whose automatic
reset would put every model back to its spawn pose and set the time to 0) is undone: the
last good state comes back and the time runs on. And since MjSpec keeps memory for every
attach/delete, the spec is rebuilt from the live models' sources after enough deletions."""
from __future__ import annotations

import ctypes
import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Dict, List, Optional, Tuple

import mujoco
import numpy as np

from .frames import Pose, Twist, all_finite, quat_conj, rotate, twist_relative, twist_to_world
from .limits import joint_command_problem, pose_problem, twist_problem
from .sdf import SdfError, sdf_to_mjcf
from .appearance import urdf_link_colours
from .urdf import PluginSpec, UrdfError, inspect_urdf

if TYPE_CHECKING:  # sensors are handed in by the plugins; the world only lends them its state
    from .camera import BodyCamera
    from .free_camera import FreeCamera
    from .lidar import Lidar

WORLD_FRAMES = ("", "world", "map")
_NAME_RE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.\-]*$")
_QPOS_SIZE = {int(mujoco.mjtJoint.mjJNT_FREE): 7, int(mujoco.mjtJoint.mjJNT_BALL): 4,
              int(mujoco.mjtJoint.mjJNT_SLIDE): 1, int(mujoco.mjtJoint.mjJNT_HINGE): 1}
#: deletions (attach/delete pairs MjSpec keeps memory for) tolerated before the spec is rebuilt
#: from scratch; rebuilding costs one parse per live model, so it waits for at least as many
#: deletions as there are live models (amortised: O(1) parses per delete, memory O(live)).
MIN_DELETIONS_BEFORE_REBUILD = 32
_UNSTABLE = (mujoco.mjtWarning.mjWARN_BADQPOS, mujoco.mjtWarning.mjWARN_BADQVEL, mujoco.mjtWarning.mjWARN_BADQACC)
_UNSTABLE_SLICE = slice(min(map(int, _UNSTABLE)), max(map(int, _UNSTABLE)) + 1)
assert _UNSTABLE_SLICE.stop - _UNSTABLE_SLICE.start == len(_UNSTABLE)  # contiguous in mjtWarning
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
    body: object = None           # MjsBody (root) in the spec
    source: str = ""              # the text MjSpec.from_string loads (URDF, or the SDF's MJCF)
    colours: Dict[str, Tuple[float, float, float, float]] = field(default_factory=dict)
    friction: Dict[str, float] = field(default_factory=dict)
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
        self._timestep, self._gravity = timestep, list(gravity)
        self.spec, self._frame = self._new_spec()
        self.models: Dict[str, ModelEntry] = {}
        self._actuation: Dict[str, Tuple[float, Tuple[float, float, float], float, Optional[float]]] = {}
        self.model: mujoco.MjModel = self.spec.compile()
        self.data = mujoco.MjData(self.model)
        self.paused = False
        self._kinematics_stale = False
        self._deletions = 0
        self.divergences = 0          # steps undone because the physics diverged
        self.last_divergence = ""     # what MuJoCo said about the last one
        self._diverged_in_a_row = 0
        self._save_good_state()

    def _new_spec(self) -> Tuple[mujoco.MjSpec, object]:
        """An empty world spec and the one frame every model is attached to (a frame per model
        would stay behind in the spec when its model is deleted: MjSpec cannot delete frames)."""
        spec = mujoco.MjSpec()
        spec.option.timestep = self._timestep
        spec.option.gravity = self._gravity
        # implicit in velocity: stiff wheel velocity servos on light wheels stay stable at 1 ms
        spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
        spec.compiler.fusestatic = False
        spec.compiler.discardvisual = True
        spec.visual.global_.offwidth = 640
        spec.visual.global_.offheight = 480
        spec.worldbody.add_light(pos=[0, 0, 10], dir=[0, 0, -1], type=mujoco.mjtLightType.mjLIGHT_DIRECTIONAL)
        return spec, spec.worldbody.add_frame()

    # ---- time -------------------------------------------------------------------------
    @property
    def time(self) -> float:
        return float(self.data.time)

    @property
    def timestep(self) -> float:
        return float(self.model.opt.timestep)

    def step(self, n: int = 1) -> None:
        """n physics steps. If they diverge (MuJoCo's instability check: NaN, inf or above 1e10
        in qpos, qvel or qacc; or a MuJoCo error), the last good state comes back and the time
        still advances by n steps: the clock never runs backwards and no model jumps to its
        spawn pose (MuJoCo's own reset would do both)."""
        start = self.data.time
        counts = self.data.warning.number  # a view: written through
        counts[_UNSTABLE_SLICE] = 0
        try:
            mujoco.mj_step(self.model, self.data, nstep=n)
            diverged = self._unstable_warning() if counts[_UNSTABLE_SLICE].any() else ""
        except mujoco.FatalError as exc:
            diverged = "MuJoCo error: %s" % exc
        # mj_step leaves body poses/velocities as they were *before* its last integration
        self._kinematics_stale = True
        if diverged or self.data.time < start:
            self._restore_good_state(start + n * self.model.opt.timestep, diverged or "the time went back")
        else:
            self._diverged_in_a_row = 0
            self._save_good_state()

    def _unstable_warning(self) -> str:
        for warning in _UNSTABLE:
            stat = self.data.warning[warning]
            if stat.number:
                kind = mujoco.mjtWarning(warning).name[len("mjWARN_BAD"):]
                return "Nan, Inf or huge value in %s at DOF %d%s" % (kind, stat.lastinfo, self._dof_owner(stat.lastinfo))
        return ""

    def _dof_owner(self, dof: int) -> str:
        if not 0 <= dof < self.model.nv:
            return ""
        body = self.model.body(int(self.model.dof_bodyid[dof])).name
        return " (model [%s])" % body.split("::")[0]

    def _save_good_state(self) -> None:
        d = self.data
        self._good = (d.qpos.copy(), d.qvel.copy(), d.act.copy(), d.qacc_warmstart.copy())

    def _restore_good_state(self, now: float, reason: str) -> None:
        """Back to the last good state at time `now`; at rest if that state diverged already."""
        self.divergences += 1
        self._diverged_in_a_row += 1
        self.last_divergence = "physics diverged (%s); restored the last good state" % reason
        qpos, qvel, act, warmstart = self._good
        mujoco.mj_resetData(self.model, self.data)
        self.data.qpos[:], self.data.act[:], self.data.qacc_warmstart[:] = qpos, act, warmstart
        self.data.qvel[:] = qvel if self._diverged_in_a_row == 1 else 0.0
        self.data.time = now
        self._apply_actuation()
        mujoco.mj_forward(self.model, self.data)
        self._kinematics_stale = False

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
        problem = pose_problem(pose.position, pose.orientation)
        if problem:
            raise WorldError("initial pose of %s: %s" % (name, problem))
        fmt = detect_format(xml)
        plugins: List[PluginSpec] = []
        friction: Dict[str, float] = {}
        colours: Dict[str, Tuple[float, float, float, float]] = {}
        joints: List[str] = []
        try:
            if fmt == "urdf":
                info = inspect_urdf(xml)
                source = xml
                fixed, plugins, friction = info.fixed_to_world, info.plugins, info.friction
                colours = urdf_link_colours(xml)  # cosmetic: what the camera sees
                joints = [j for j, t in info.joints.items() if t in ("revolute", "continuous", "prismatic")]
                model_offset = Pose()
            else:
                converted = sdf_to_mjcf(xml)
                source = converted.mjcf
                fixed, model_offset = converted.static, converted.pose
            child = _load_child(source, colours, friction)
        except (UrdfError, SdfError) as exc:
            raise WorldError(str(exc)) from exc
        except Exception as exc:  # MuJoCo's parser: mujoco.FatalError / ValueError
            raise WorldError("MuJoCo cannot load the %s: %s" % (fmt.upper(), exc)) from exc
        root = child.worldbody.first_body()
        if root is None:
            raise WorldError("model %s has no bodies" % name)
        body_local = Pose(np.array(root.pos), np.array(root.quat))
        frame_pose = pose.compose(model_offset)
        world_body_pose = frame_pose.compose(body_local)
        entry = ModelEntry(name=name, fmt=fmt, fixed=fixed, root_body=name + "::" + root.name,
                           spawn_pose=world_body_pose, body_local=body_local, joints=joints, plugins=plugins,
                           robot_namespace=robot_namespace, source=source, colours=colours, friction=friction)
        self._attach(entry, root, world_body_pose)
        self.models[name] = entry
        try:
            self._recompile()
        except Exception as exc:
            self._remove_from_spec(entry)
            del self.models[name]
            raise WorldError("MuJoCo cannot compile model %s: %s" % (name, exc)) from exc
        return entry

    def _attach(self, entry: ModelEntry, root, world_body_pose: Pose) -> None:
        """Put a model's root body (of its own loaded spec) into the world spec at a world pose."""
        body = self._frame.attach_body(root, entry.name + "::", "")
        body.pos, body.quat = world_body_pose.position, world_body_pose.orientation
        if not entry.fixed:
            body.add_freejoint(name=entry.name + "::__root__")
        for joint in entry.joints:
            self.spec.add_actuator(name="%s::%s" % (entry.name, joint), target="%s::%s" % (entry.name, joint),
                                   trntype=mujoco.mjtTrn.mjTRN_JOINT, biastype=mujoco.mjtBias.mjBIAS_AFFINE,
                                   gainprm=[0.0] * 10)  # passive until a controller commands it
        entry.body = body

    def delete(self, name: str) -> None:
        entry = self.models.get(name)
        if entry is None:
            raise WorldError("model [%s] does not exist" % name)
        self._remove_from_spec(entry)
        del self.models[name]
        for key in [k for k in self._actuation if k.startswith(name + "::")]:
            del self._actuation[key]
        self._deletions += 1
        if self._deletions >= max(MIN_DELETIONS_BEFORE_REBUILD, len(self.models)):
            self._rebuild_spec()
        self._recompile()

    def _remove_from_spec(self, entry: ModelEntry) -> None:
        for act in list(self.spec.actuators):
            if act.name.startswith(entry.name + "::"):
                self.spec.delete(act)
        self.spec.delete(entry.body)

    def _rebuild_spec(self) -> None:
        """A fresh spec holding only the live models (reloaded from their sources, fixed ones
        where they are now): MjSpec frees what deleted models left behind only with the spec."""
        placed = {name: Pose(np.array(e.body.pos), np.array(e.body.quat)) for name, e in self.models.items()}
        self.spec, self._frame = self._new_spec()
        for name, entry in self.models.items():
            child = _load_child(entry.source, entry.colours, entry.friction)
            self._attach(entry, child.worldbody.first_body(), placed[name])
        self._deletions = 0
        _return_freed_memory()

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
        self._kinematics_stale = False
        self._save_good_state()

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
        if not all_finite(np.array([gain, *bias])):
            raise WorldError("non-finite gains for %s::%s" % (model, joint))
        problem = joint_command_problem(ctrl)
        if problem:
            raise WorldError("%s::%s: %s" % (model, joint, problem))
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

    def link_id(self, model: str, link: Optional[str]) -> int:
        """Body id of link `link` (unscoped) of model `model`, -1 when there is none. Ids change
        when a spawn or delete recompiles the world: ask again rather than keep one."""
        return self._body_id("%s::%s" % (model, link))

    @property
    def gravity(self) -> np.ndarray:
        return np.array(self.model.opt.gravity)

    def scan(self, lidar: "Lidar", link: int) -> np.ndarray:
        """One scan of `lidar` mounted on body `link` (an id from link_id)."""
        return lidar.scan(self.model, self.data, link)

    def render(self, camera: "BodyCamera", link: int) -> np.ndarray:
        """One RGB image of `camera` mounted on body `link` (an id from link_id)."""
        return camera.render(self.model, self.data, link)

    def prepare(self, camera: "FreeCamera") -> None:
        """Set a free camera up for the current model; needs no lock (a spawn replaces the model
        object, it does not change this one's meshes)."""
        camera.prepare(self.model)

    def capture(self, camera: "FreeCamera") -> None:
        """Copy the current scene into a free camera (its cheap half; it draws outside the lock)."""
        self._refresh_kinematics()
        camera.capture(self.model, self.data)

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
        problem = pose_problem(pose.position, pose.orientation) or twist_problem(twist.linear, twist.angular)
        if problem:
            raise WorldError("model [%s]: %s" % (name, problem))
        try:
            ref_pose, _ = self.frame_state(reference_frame)
        except WorldError as exc:
            raise WorldError("reference frame [%s] not found: %s" % (reference_frame, exc)) from exc
        if self.entity_body(name) == (self.entity_body(reference_frame) if reference_frame not in WORLD_FRAMES else -1):
            raise WorldError("model [%s] cannot be set relative to itself" % name)
        world_pose = ref_pose.compose(pose)
        world_twist = twist_to_world(twist, ref_pose)
        problem = pose_problem(world_pose.position, world_pose.orientation)  # relative to a far-off model
        if problem:
            raise WorldError("model [%s] in the world frame: %s" % (name, problem))
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
        self._kinematics_stale = False  # the good state stays the one before: the next step proves this one

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
        self._kinematics_stale = False
        self._save_good_state()

    def reset_simulation(self) -> None:
        self.reset_world()
        self.data.time = 0.0


def _return_freed_memory() -> None:
    """Hand the old spec's freed heap back to the system (glibc keeps MjSpec's many small
    blocks otherwise: RSS grew 30 MB per 200 spawn/delete pairs though nothing leaked)."""
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass  # not glibc: nothing to do


def _load_child(source: str, colours: Dict[str, Tuple[float, float, float, float]],
                friction: Dict[str, float]) -> mujoco.MjSpec:
    """A model's own spec from its source text, with the URDF's colours and friction applied."""
    child = mujoco.MjSpec.from_string(source)
    for body in child.bodies:
        if body.name in colours:
            for geom in body.geoms:
                geom.rgba = list(colours[body.name])
        if body.name in friction:
            for geom in body.geoms:
                geom.friction = [friction[body.name], geom.friction[1], geom.friction[2]]
    return child
