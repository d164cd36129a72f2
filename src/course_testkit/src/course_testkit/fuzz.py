"""Hypothesis strategies for fuzzing ROS handlers: wild numbers, names and XML.

Every fuzz test of the course (turtlesim, gazebo, the relay, patrol, the drawer,
the add/progress servers) draws its inputs from here, so "huge", "NaN" and
"not a ROS name" mean the same thing everywhere. Pure strategies: no rospy.
"""
from __future__ import annotations

import math
import struct

from hypothesis import HealthCheck, Phase, settings
from hypothesis import strategies as st

FLOAT32_MAX = 3.4028234663852886e38
INT32 = (-2**31, 2**31 - 1)
INT64 = (-2**63, 2**63 - 1)

#: Values that broke our nodes before, or break float32 packing and angle wrapping.
EDGE_FLOATS = (0.0, -0.0, 1e-300, -1e-300, 1.0, -1.0, math.pi, -math.pi, 2 * math.pi,
               1e18, -1e18, 1e30, -1e30, FLOAT32_MAX, -FLOAT32_MAX, 3.5e38, -3.5e38,
               1e308, -1e308, math.inf, -math.inf, math.nan)


def finite_floats() -> st.SearchStrategy[float]:
    """Any finite float64, with the edges above (not inf/nan) drawn often."""
    return st.one_of(st.sampled_from([v for v in EDGE_FLOATS if math.isfinite(v)]),
                     st.floats(allow_nan=False, allow_infinity=False),
                     st.floats(min_value=-100.0, max_value=100.0))


def wild_floats() -> st.SearchStrategy[float]:
    """Finite, huge, NaN and +-inf: whatever a float64 field of a message can carry."""
    return st.one_of(finite_floats(), st.sampled_from([math.inf, -math.inf, math.nan]),
                     st.floats(allow_nan=True, allow_infinity=True))


def as_float32(value: float) -> float:
    """What a float64 becomes in a float32 message field, held within float32's range (a finite
    value beyond it cannot even be sent: genpy raises OverflowError); inf and NaN pass as they are."""
    if math.isfinite(value):
        value = min(max(value, -FLOAT32_MAX), FLOAT32_MAX)
    return struct.unpack("<f", struct.pack("<f", value))[0]


def wild_float32s() -> st.SearchStrategy[float]:
    """wild_floats() as a float32 field carries them: finite (float32's ends drawn often), NaN, +-inf."""
    return wild_floats().map(as_float32)


def wild_ints(bits: int = 32) -> st.SearchStrategy[int]:
    """Any integer a signed field of this width can carry, with its ends drawn often."""
    low, high = -2**(bits - 1), 2**(bits - 1) - 1
    return st.one_of(st.sampled_from([low, -1, 0, 1, high]), st.integers(low, high))


def valid_names() -> st.SearchStrategy[str]:
    """Names ROS accepts as a base name (letters, digits, underscores; a letter first)."""
    return st.from_regex(r"\A[A-Za-z][A-Za-z0-9_]{0,30}\Z")


def wild_names() -> st.SearchStrategy[str]:
    """Valid names, and the ones graph names forbid: empty, digits first, slashes,
    spaces, unicode, control characters, very long."""
    return st.one_of(valid_names(),
                     st.sampled_from(["", "1turtle", "/", "//", "a/", "a b", "~", "ü", "a-b",
                                      "\x00", "\n", "turtle1", "x" * 5000]),
                     st.text(max_size=40))


def wild_xml() -> st.SearchStrategy[str]:
    """Model descriptions that are not what they claim: empty, not XML, unclosed, the
    wrong root, deep nesting, huge numbers in attributes, entities."""
    numbers = st.sampled_from(["1e308", "nan", "inf", "-1", "0", "abc", "1e30"])
    snippets = st.one_of(
        st.sampled_from(["", "not xml", "<", "<robot>", "<sdf>", "<robot name='r'></robot>",
                         "<sdf version='1.6'><model name='m'/></sdf>",
                         "<!DOCTYPE x [<!ENTITY a 'aaaaaaaaaa'>]><robot>&a;</robot>",
                         "<a>" * 200 + "</a>" * 200]),
        numbers.map(lambda v: "<sdf version='1.6'><model name='m'><link name='l'><inertial>"
                              "<mass>%s</mass></inertial><collision name='c'><geometry><box>"
                              "<size>%s 1 1</size></box></geometry></collision></link></model>"
                              "</sdf>" % (v, v)),
        numbers.map(lambda v: "<robot name='r'><link name='l'><inertial><mass value='%s'/>"
                              "</inertial><collision><geometry><sphere radius='%s'/></geometry>"
                              "</collision></link></robot>" % (v, v)),
        st.text(max_size=200))
    return snippets


def live_node_settings(max_examples: int) -> settings:
    """Hypothesis settings for fuzzing a running node from a rostest: reproducible, nothing
    stored, no deadline, no shrinking (each example costs real time on a live node; the first
    failing one is reported as it is, within the .test's time limit)."""
    return settings(max_examples=max_examples, deadline=None, derandomize=True, database=None,
                    phases=[Phase.explicit, Phase.generate], suppress_health_check=list(HealthCheck))


def is_wrapped_angle(theta: float) -> bool:
    """True for an angle in [-pi, pi] (turtlesim's and tf's normal form)."""
    return math.isfinite(theta) and -math.pi - 1e-6 <= theta <= math.pi + 1e-6


def is_sane_pose(pose) -> bool:
    """True for a turtlesim Pose (anything with its five fields) whose fields are all finite and
    whose theta is wrapped: what every fuzz check asks of turtlesim after each example."""
    fields = (pose.x, pose.y, pose.theta, pose.linear_velocity, pose.angular_velocity)
    return all(math.isfinite(v) for v in fields) and is_wrapped_angle(pose.theta)
