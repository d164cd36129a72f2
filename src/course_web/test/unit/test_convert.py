"""course_web.convert: JSON <-> ROS messages, rosbridge's way, strict on the way in."""
from __future__ import annotations

import base64
import json
import math

import genpy
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from course_web.convert import (BYTE_ARRAY_BASES, INT_RANGES, ConversionError, _array, json_to_message,
                                message_class, message_to_json)

ROUND_TRIP_TYPES = ["std_msgs/Header", "geometry_msgs/Twist", "geometry_msgs/PoseStamped",
                    "sensor_msgs/Image", "sensor_msgs/JointState", "sensor_msgs/CameraInfo",
                    "std_msgs/UInt8MultiArray", "std_msgs/Int64MultiArray", "std_msgs/Duration",
                    "rosgraph_msgs/Log", "turtlesim/Pose", "std_msgs/Char", "std_msgs/Bool"]


def value_strategy(slot_type: str) -> st.SearchStrategy:
    """Any valid value of a message field, as genpy holds it."""
    base, size = _array(slot_type)
    if base is not None:
        if base in BYTE_ARRAY_BASES:
            return st.binary(min_size=size or 0, max_size=size if size is not None else 40)
        items = value_strategy(base)
        return st.lists(items, min_size=size or 0, max_size=size if size is not None else 4)
    if slot_type in INT_RANGES:
        return st.integers(*INT_RANGES[slot_type])
    if slot_type in ("float32", "float64"):
        return st.floats(allow_nan=False, allow_infinity=False)
    if slot_type == "bool":
        return st.booleans()
    if slot_type == "string":
        return st.text(max_size=20)
    if slot_type == "time":
        return st.builds(genpy.Time, st.integers(0, 2 ** 32 - 1), st.integers(0, 999999999))
    if slot_type == "duration":
        return st.builds(genpy.Duration, st.integers(-2 ** 31, 2 ** 31 - 1), st.integers(0, 999999999))
    return message_strategy(message_class("std_msgs/Header" if slot_type == "Header" else slot_type))


def message_strategy(cls) -> st.SearchStrategy:
    fields = {name: value_strategy(slot) for name, slot in zip(cls.__slots__, cls._slot_types)}
    return st.fixed_dictionaries(fields).map(lambda values: cls(**values))


@pytest.mark.parametrize("type_name", ROUND_TRIP_TYPES)
def test_every_message_survives_the_round_trip_through_json_text(type_name):
    cls = message_class(type_name)

    @settings(max_examples=60, deadline=None)
    @given(message_strategy(cls))
    def round_trip(msg):
        text = json.dumps(message_to_json(msg), allow_nan=False)
        assert json_to_message(json.loads(text), cls, message_class) == msg
    round_trip()


def test_rosbridge_shapes_time_bytes_and_nested_messages():
    image = message_class("sensor_msgs/Image")(data=b"\x00\xff\x10", encoding="rgb8")
    image.header.stamp = genpy.Time(12, 345)
    data = message_to_json(image)
    assert data["header"]["stamp"] == {"secs": 12, "nsecs": 345}
    assert data["data"] == base64.b64encode(b"\x00\xff\x10").decode()
    assert data["encoding"] == "rgb8"


def test_a_byte_array_may_also_come_as_a_list_of_numbers():
    image = json_to_message({"data": [1, 2, 255]}, message_class("sensor_msgs/Image"), message_class)
    assert image.data == b"\x01\x02\xff"


def test_non_finite_floats_go_out_as_null_and_null_comes_back_as_nan():
    twist = message_class("geometry_msgs/Twist")()
    twist.linear.x = math.nan
    twist.angular.z = math.inf
    data = message_to_json(twist)
    assert data["linear"]["x"] is None and data["angular"]["z"] is None
    json.dumps(data, allow_nan=False)
    assert math.isnan(json_to_message(data, type(twist), message_class).linear.x)


@pytest.mark.parametrize("data, complaint", [
    ({"linear": {"x": "fast"}}, "linear.x: expected a number (float64), got a string"),
    ({"linear": {"x": True}}, "linear.x: expected a number"),
    ({"linear": 3}, "linear: expected an object for geometry_msgs/Vector3"),
    ({"linear": {"w": 1}}, "linear: geometry_msgs/Vector3 has no field w"),
    ({"speed": 1}, "message: geometry_msgs/Twist has no field speed"),
    ([1, 2], "message: expected an object"),
])
def test_a_wrong_field_is_refused_with_its_path(data, complaint):
    with pytest.raises(ConversionError, match=complaint.replace("(", r"\(").replace(")", r"\)")):
        json_to_message(data, message_class("geometry_msgs/Twist"), message_class)


@pytest.mark.parametrize("type_name, data, complaint", [
    ("std_msgs/UInt8", {"data": 256}, "out of range for uint8"),
    ("std_msgs/Int8", {"data": -129}, "out of range for int8"),
    ("std_msgs/Int32", {"data": 1.5}, "expected an integer"),
    ("std_msgs/String", {"data": 5}, "expected a string"),
    ("std_msgs/Bool", {"data": 1}, "expected true or false"),
    ("std_msgs/Time", {"data": {"secs": 1, "sec": 2}}, "expected {"),
    ("std_msgs/Time", {"data": {"secs": -1}}, "out of range"),
    ("sensor_msgs/Image", {"data": "not base64!"}, "expected base64"),
    ("sensor_msgs/CameraInfo", {"K": [1.0, 2.0]}, "K: expected 9 items, got 2"),
    ("sensor_msgs/JointState", {"position": [1.0, "x"]}, r"position\[1\]: expected a number"),
])
def test_values_that_do_not_fit_their_type_are_refused(type_name, data, complaint):
    with pytest.raises(ConversionError, match=complaint):
        json_to_message(data, message_class(type_name), message_class)


def test_missing_fields_keep_their_defaults():
    twist = json_to_message({"linear": {"x": 1.5}}, message_class("geometry_msgs/Twist"), message_class)
    assert (twist.linear.x, twist.linear.y, twist.angular.z) == (1.5, 0.0, 0.0)
