"""Text of one tf2_echo sample, in the layout of the ROS 2 / C++ tf2_echo tool.

`tf2_echo SOURCE TARGET` prints the pose of TARGET in SOURCE (lookup_transform(SOURCE, TARGET)).
"""
from __future__ import annotations

import math
from typing import Sequence

from turtle_tf2.geometry import euler_from_quaternion


def _vector(values: Sequence[float], precision: int) -> str:
    return "[" + ", ".join("%.*f" % (precision, v) for v in values) + "]"


def format_sample(stamp_s: float, translation: Sequence[float], rotation: Sequence[float],
                  precision: int = 3) -> str:
    """Lines describing one transform: time, translation, quaternion, RPY in radians and degrees."""
    rpy = euler_from_quaternion(tuple(rotation))  # type: ignore[arg-type]
    return "\n".join([
        "At time %.*f" % (precision, stamp_s),
        "- Translation: " + _vector(translation, precision),
        "- Rotation: in Quaternion " + _vector(rotation, precision),
        "- Rotation: in RPY (radian) " + _vector(rpy, precision),
        "- Rotation: in RPY (degree) " + _vector([math.degrees(a) for a in rpy], precision),
    ])
