"""SDF model -> MJCF conversion (the primitives the course needs).

Supported: <model> with <static>, <pose>; <link> with <pose>, <inertial> (mass, inertia,
pose), <collision>/<visual> with box, cylinder, sphere and plane geometry and <pose>,
collision <surface><friction><ode><mu>; <joint> revolute/continuous/prismatic/fixed/ball
between links (other links are welded to the first). Meshes are refused with a clear error.
Poses follow SDF 1.6: link poses relative to the model, collision/visual/inertial poses
relative to their link, joint axes in the child link frame.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Optional
from xml.sax.saxutils import quoteattr

import numpy as np

from .frames import Pose, quat_from_rpy, quat_to_matrix


class SdfError(ValueError):
    """The SDF text cannot be turned into a MuJoCo model."""


@dataclass
class SdfModel:
    """The result of a conversion: MJCF text plus what the world needs to know."""

    name: str
    mjcf: str
    static: bool
    pose: Pose
    link_names: List[str] = field(default_factory=list)


def parse_pose(text: Optional[str]) -> Pose:
    """SDF '<pose>x y z roll pitch yaw</pose>' -> Pose (missing -> identity)."""
    if text is None or not text.strip():
        return Pose()
    try:
        vals = [float(v) for v in text.split()]
    except ValueError as exc:
        raise SdfError("bad <pose> %r" % text) from exc
    if len(vals) != 6 or not all(math.isfinite(v) for v in vals):
        raise SdfError("<pose> needs 6 finite numbers, got %r" % text)
    return Pose(vals[:3], quat_from_rpy(*vals[3:]))


def _fmt(values) -> str:
    return " ".join("%.9g" % float(v) for v in values)


def _float(elem: Optional[ET.Element], default: float) -> float:
    if elem is None or elem.text is None:
        return default
    try:
        val = float(elem.text)
    except ValueError as exc:
        raise SdfError("bad number %r in <%s>" % (elem.text, elem.tag)) from exc
    if not math.isfinite(val):
        raise SdfError("non-finite number in <%s>" % elem.tag)
    return val


def _geom_attrs(geometry: Optional[ET.Element], where: str) -> str:
    if geometry is None or len(geometry) == 0:
        raise SdfError("%s has no <geometry>" % where)
    shape = geometry[0]
    if shape.tag == "box":
        size = [float(v) / 2 for v in (shape.findtext("size") or "1 1 1").split()]
        if len(size) != 3:
            raise SdfError("%s: <box><size> needs 3 numbers" % where)
        return 'type="box" size=%s' % quoteattr(_fmt(size))
    if shape.tag == "cylinder":
        return 'type="cylinder" size=%s' % quoteattr(_fmt([_float(shape.find("radius"), 1.0),
                                                          _float(shape.find("length"), 1.0) / 2]))
    if shape.tag == "sphere":
        return 'type="sphere" size=%s' % quoteattr(_fmt([_float(shape.find("radius"), 1.0)]))
    if shape.tag == "plane":
        return 'type="plane" size="0 0 1"'
    raise SdfError("%s: geometry <%s> is not supported (box, cylinder, sphere, plane)" % (where, shape.tag))


def _inertial_xml(link: ET.Element) -> str:
    inertial = link.find("inertial")
    mass, pose, inertia = 1.0, Pose(), [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]
    if inertial is not None:
        mass = _float(inertial.find("mass"), 1.0)
        pose = parse_pose(inertial.findtext("pose"))
        tensor = inertial.find("inertia")
        if tensor is not None:
            inertia = [_float(tensor.find(k), d) for k, d in
                       (("ixx", 1.0), ("iyy", 1.0), ("izz", 1.0), ("ixy", 0.0), ("ixz", 0.0), ("iyz", 0.0))]
    if mass <= 0:
        raise SdfError("link %r: mass must be positive" % link.get("name"))
    ixx, iyy, izz, ixy, ixz, iyz = inertia
    tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
    rot = quat_to_matrix(pose.orientation)
    tensor = rot @ tensor @ rot.T  # MJCF's fullinertia is given in the link frame
    full = [tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1], tensor[0, 2], tensor[1, 2]]
    return '<inertial pos=%s mass="%.9g" fullinertia=%s/>' % (
        quoteattr(_fmt(pose.position)), mass, quoteattr(_fmt(full)))


def _visual_rgba(visual: ET.Element) -> str:
    """' rgba="..."' from a visual's <material><diffuse> (else <ambient>), '' when it has none."""
    for tag in ("material/diffuse", "material/ambient"):
        try:
            values = [float(v) for v in (visual.findtext(tag) or "").split()]
        except ValueError:
            continue  # colour is cosmetic, never an error
        if len(values) in (3, 4) and all(0.0 <= v <= 1.0 for v in values):
            return ' rgba=%s' % quoteattr(_fmt(values + [1.0] * (4 - len(values))))
    return ""


def _link_geoms_xml(link: ET.Element) -> List[str]:
    """The link's collision and visual geoms. The world discards visual geoms (discardvisual),
    so, as for a URDF (appearance.py), the collision geoms take the colour of the link's first
    visual with a <material>: what the cameras see."""
    out = []
    lname = link.get("name", "link")
    colour = next((c for c in map(_visual_rgba, link.findall("visual")) if c), "")
    for tag, extra in (("collision", colour), ("visual", ' contype="0" conaffinity="0" group="1" mass="0"')):
        for i, elem in enumerate(link.findall(tag)):
            where = "link %r %s %r" % (lname, tag, elem.get("name", str(i)))
            pose = parse_pose(elem.findtext("pose"))
            friction = ""
            mu = elem.find("surface/friction/ode/mu")
            if tag == "collision" and mu is not None:
                friction = ' friction="%.9g 0.005 0.0001"' % _float(mu, 1.0)
            out.append('<geom %s pos=%s quat=%s%s%s/>' % (
                _geom_attrs(elem.find("geometry"), where), quoteattr(_fmt(pose.position)),
                quoteattr(_fmt(pose.orientation)), friction, extra))
    return out


_JOINT_TYPES = {"revolute": "hinge", "continuous": "hinge", "prismatic": "slide", "ball": "ball"}


def _parse(text: str, what: str) -> ET.Element:
    """The XML root of `text`; malformed XML becomes an SdfError naming `what` it should have been."""
    try:
        return ET.fromstring(text)
    except ET.ParseError as exc:
        raise SdfError("malformed %s: %s" % (what, exc)) from exc


def sdf_to_mjcf(sdf_text: str) -> SdfModel:
    """Convert the first <model> of an SDF document into MJCF text."""
    root = _parse(sdf_text, "SDF XML")
    model = root if root.tag == "model" else root.find("model")
    if model is None:
        model = root.find("world/model")
    if model is None:
        raise SdfError("no <model> element in SDF")
    name = model.get("name") or "model"
    static = (model.findtext("static") or "false").strip().lower() in ("1", "true")
    links = model.findall("link")
    if not links:
        raise SdfError("model %r has no <link>" % name)
    link_by_name: Dict[str, ET.Element] = {}
    for link in links:
        lname = link.get("name")
        if not lname or lname in link_by_name:
            raise SdfError("model %r: links need unique names" % name)
        link_by_name[lname] = link
    link_pose = {n: parse_pose(l.findtext("pose")) for n, l in link_by_name.items()}

    parent_of: Dict[str, str] = {}
    joint_of: Dict[str, ET.Element] = {}
    for joint in model.findall("joint"):
        parent, child = joint.findtext("parent"), joint.findtext("child")
        if child not in link_by_name or (parent not in link_by_name and parent != "world"):
            raise SdfError("joint %r links unknown links %r -> %r" % (joint.get("name"), parent, child))
        if parent == "world":
            continue
        jtype = joint.get("type", "")
        if jtype not in _JOINT_TYPES and jtype != "fixed":
            raise SdfError("joint %r: type %r not supported" % (joint.get("name"), jtype))
        parent_of[child] = parent
        joint_of[child] = joint
    root_link = links[0].get("name")
    for lname in link_by_name:
        if lname != root_link and lname not in parent_of:
            parent_of[lname] = root_link  # unconnected links are welded to the canonical link
    children: Dict[str, List[str]] = {}
    for child, parent in parent_of.items():
        children.setdefault(parent, []).append(child)
    if root_link in parent_of:
        raise SdfError("model %r: the first link cannot be a joint child" % name)

    def body_xml(lname: str, seen: set) -> str:
        if lname in seen:
            raise SdfError("model %r: joint loop at link %r" % (name, lname))
        seen.add(lname)
        link = link_by_name[lname]
        parent = parent_of.get(lname)
        rel = link_pose[lname] if parent is None else link_pose[lname].relative_to(link_pose[parent])
        parts = [_inertial_xml(link)]
        joint = joint_of.get(lname)
        if joint is not None and joint.get("type") in _JOINT_TYPES:
            jpose = parse_pose(joint.findtext("pose"))
            axis_text = joint.findtext("axis/xyz") or "0 0 1"
            axis = np.array([float(v) for v in axis_text.split()])
            attrs = 'name=%s type="%s" pos=%s' % (quoteattr(joint.get("name", lname + "_joint")),
                                                  _JOINT_TYPES[joint.get("type")], quoteattr(_fmt(jpose.position)))
            if joint.get("type") != "ball":
                attrs += " axis=%s" % quoteattr(_fmt(axis))
            lower, upper = joint.find("axis/limit/lower"), joint.find("axis/limit/upper")
            if joint.get("type") in ("revolute", "prismatic") and lower is not None and upper is not None:
                attrs += ' limited="true" range="%.9g %.9g"' % (_float(lower, 0.0), _float(upper, 0.0))
            damping = joint.find("axis/dynamics/damping")
            if damping is not None:
                attrs += ' damping="%.9g"' % _float(damping, 0.0)
            parts.append("<joint %s/>" % attrs)
        parts.extend(_link_geoms_xml(link))
        for child in children.get(lname, []):
            parts.append(body_xml(child, seen))
        return '<body name=%s pos=%s quat=%s>%s</body>' % (
            quoteattr(lname), quoteattr(_fmt(rel.position)), quoteattr(_fmt(rel.orientation)), "".join(parts))

    body = body_xml(root_link, set())
    mjcf = ('<mujoco model=%s><compiler angle="radian" inertiafromgeom="false"/>'
            "<worldbody>%s</worldbody></mujoco>" % (quoteattr(name), body))
    return SdfModel(name=name, mjcf=mjcf, static=static, pose=parse_pose(model.findtext("pose")),
                    link_names=list(link_by_name))


@dataclass
class WorldInclude:
    """One model a world file brings in: a database uri (model://name) or inline SDF."""

    uri: str
    name: Optional[str]
    pose: Optional[Pose]
    inline_sdf: Optional[str] = None


@dataclass
class WorldFile:
    includes: List[WorldInclude]
    max_step_size: Optional[float]
    real_time_factor: Optional[float]
    gravity: Optional[np.ndarray]


def parse_world(text: str) -> WorldFile:
    """Read an SDF world file: <include> models, inline <model>s and the <physics>/<gravity> settings."""
    root = _parse(text, "world file")
    world = root if root.tag == "world" else root.find("world")
    if world is None:
        raise SdfError("no <world> element")
    includes = []
    for inc in world.findall("include"):
        uri = (inc.findtext("uri") or "").strip()
        pose_text = inc.findtext("pose")
        includes.append(WorldInclude(uri=uri, name=inc.findtext("name"),
                                     pose=parse_pose(pose_text) if pose_text else None))
    for model in world.findall("model"):
        includes.append(WorldInclude(uri="", name=model.get("name"), pose=None,
                                     inline_sdf='<sdf version="1.6">%s</sdf>' % ET.tostring(model, encoding="unicode")))
    physics = world.find("physics")
    step = rtf = None
    if physics is not None:
        if physics.find("max_step_size") is not None:
            step = _float(physics.find("max_step_size"), 0.001)
        if physics.find("real_time_factor") is not None:
            rtf = _float(physics.find("real_time_factor"), 1.0)
    gravity = None
    gtext = world.findtext("gravity")
    if gtext:
        gravity = np.array([float(v) for v in gtext.split()])
    return WorldFile(includes=includes, max_step_size=step, real_time_factor=rtf, gravity=gravity)
