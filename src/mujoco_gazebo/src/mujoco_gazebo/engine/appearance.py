"""Colours a URDF gives its links (<visual><material><color rgba>), so the simulated camera
sees RRBot orange and black as in Gazebo rather than MuJoCo's default grey. MuJoCo keeps
only collision geoms here (visuals are discarded), so the world paints those instead."""
from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import Dict, Optional, Tuple

Rgba = Tuple[float, float, float, float]


def _rgba(material: ET.Element) -> Optional[Rgba]:
    color = material.find("color")
    if color is None:
        return None
    try:
        values = tuple(float(v) for v in (color.get("rgba") or "").split())
    except ValueError:
        return None
    if len(values) != 4 or not all(0.0 <= v <= 1.0 for v in values):
        return None
    return values  # type: ignore[return-value]


def urdf_link_colours(text: str) -> Dict[str, Rgba]:
    """Link name -> rgba of its first visual's material (inline colour, else a colour defined
    anywhere under the same material name, as URDF materials are global). Links without a
    usable colour, and unparsable text, give no entry: colour is cosmetic, never an error."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError:
        return {}
    named: Dict[str, Rgba] = {}
    for material in root.iter("material"):
        rgba = _rgba(material)
        if rgba is not None and material.get("name") and material.get("name") not in named:
            named[material.get("name")] = rgba
    colours: Dict[str, Rgba] = {}
    for link in root.findall("link"):
        material = link.find("visual/material")
        if material is None or not link.get("name"):
            continue
        rgba = _rgba(material) or named.get(material.get("name", ""))
        if rgba is not None:
            colours[link.get("name")] = rgba
    return colours
