"""What the simulator reads from a URDF besides what MuJoCo loads: whether the robot is
fixed to the world (a link named `world`, Gazebo's convention), and the `<gazebo>`
extension blocks (plugins, sensors, friction) that say which ROS interfaces to offer."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Optional


class UrdfError(ValueError):
    """The URDF text is not a usable robot description."""


@dataclass
class PluginSpec:
    """A <plugin> block: the library name it names in Gazebo and its parameters (tag -> text)."""

    filename: str
    name: str
    params: Dict[str, str]
    reference: Optional[str] = None     # link the enclosing <gazebo reference=...> names
    sensor_type: Optional[str] = None   # "ray", "imu", "camera" when inside a <sensor>
    sensor: Optional[ET.Element] = None  # the <sensor> element, for its <update_rate>, <ray>, ...


@dataclass
class UrdfInfo:
    name: str
    fixed_to_world: bool
    links: List[str]
    joints: Dict[str, str]                      # joint name -> type
    plugins: List[PluginSpec] = field(default_factory=list)
    friction: Dict[str, float] = field(default_factory=dict)  # link -> mu1


def _params(plugin: ET.Element) -> Dict[str, str]:
    return {child.tag: (child.text or "").strip() for child in plugin}


def inspect_urdf(text: str) -> UrdfInfo:
    """Parse the parts of a URDF the simulator uses; raises UrdfError on malformed input."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise UrdfError("malformed URDF XML: %s" % exc) from exc
    if root.tag != "robot":
        raise UrdfError("URDF root element must be <robot>, got <%s>" % root.tag)
    links = [l.get("name") for l in root.findall("link")]
    if not links or any(not n for n in links):
        raise UrdfError("URDF needs named <link> elements")
    if len(set(links)) != len(links):
        raise UrdfError("URDF has duplicate link names")
    joints: Dict[str, str] = {}
    for j in root.findall("joint"):
        jname, parent, child = j.get("name"), j.find("parent"), j.find("child")
        if not jname or parent is None or child is None:
            raise UrdfError("URDF joint %r needs a name, <parent> and <child>" % jname)
        if parent.get("link") not in links or child.get("link") not in links:
            raise UrdfError("URDF joint %r names an unknown link" % jname)
        joints[jname] = j.get("type", "")
    info = UrdfInfo(name=root.get("name", "robot"), fixed_to_world="world" in links,
                    links=[l for l in links if l != "world"], joints=joints)
    for gz in root.findall("gazebo"):
        ref = gz.get("reference")
        mu = gz.findtext("mu1")
        if ref and mu:
            try:
                info.friction[ref] = float(mu)
            except ValueError as exc:
                raise UrdfError("bad <mu1> for %r" % ref) from exc
        for plugin in gz.findall("plugin"):
            info.plugins.append(PluginSpec(plugin.get("filename", ""), plugin.get("name", ""),
                                           _params(plugin), reference=ref))
        for sensor in gz.findall("sensor"):
            for plugin in sensor.findall("plugin"):
                info.plugins.append(PluginSpec(plugin.get("filename", ""), plugin.get("name", ""),
                                               _params(plugin), reference=ref,
                                               sensor_type=sensor.get("type"), sensor=sensor))
    return info
