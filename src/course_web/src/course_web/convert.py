"""ROS messages <-> JSON-ready Python values, for any message class genpy generated.

The rules are rosbridge's, so its clients (roslibpy, roslibjs) read and write the same JSON:
a message is an object of its fields; time and duration are {"secs", "nsecs"}; uint8[] and
char[] (fixed or variable length) travel as base64 strings; every other array is a list.
JSON has no NaN or infinity, so a non-finite float goes out as null (and null comes back as
NaN). Reading is strict: a field of the wrong type, an integer out of its range or a field the
message does not have raises ConversionError naming the field's path, because a silently
zeroed command is worse than a clear refusal.
"""
from __future__ import annotations

import base64
import binascii
import math
import re
from typing import Any, Callable, Dict, Optional, Type

import genpy
import roslib.message

INT_RANGES = {
    "int8": (-2 ** 7, 2 ** 7 - 1), "uint8": (0, 2 ** 8 - 1), "byte": (-2 ** 7, 2 ** 7 - 1),
    "char": (0, 2 ** 8 - 1), "int16": (-2 ** 15, 2 ** 15 - 1), "uint16": (0, 2 ** 16 - 1),
    "int32": (-2 ** 31, 2 ** 31 - 1), "uint32": (0, 2 ** 32 - 1),
    "int64": (-2 ** 63, 2 ** 63 - 1), "uint64": (0, 2 ** 64 - 1),
}
FLOAT_TYPES = ("float32", "float64")
BYTE_ARRAY_BASES = ("uint8", "char")
TIME_TYPES = {"time": genpy.Time, "duration": genpy.Duration}
ARRAY = re.compile(r"^(?P<base>[^\[]+)\[(?P<size>\d*)\]$")

MessageClassLookup = Callable[[str], Optional[Type[genpy.Message]]]


def message_class(type_name: str) -> Optional[Type[genpy.Message]]:
    """The class of a message type name ("pkg/Name"), or None when no such message is installed."""
    try:
        return roslib.message.get_message_class(type_name)
    except (ValueError, ImportError, AttributeError, TypeError):
        return None


def service_class(type_name: str):
    """The class of a service type name, or None."""
    try:
        return roslib.message.get_service_class(type_name)
    except (ValueError, ImportError, AttributeError, TypeError):
        return None


class ConversionError(ValueError):
    """A JSON value does not fit the message field it is meant for."""


def _array(slot_type: str):
    match = ARRAY.match(slot_type)
    if match is None:
        return None, None
    size = match.group("size")
    return match.group("base"), (int(size) if size else None)


def _message_class(type_name: str, lookup: MessageClassLookup) -> Type[genpy.Message]:
    if type_name == "Header":
        type_name = "std_msgs/Header"
    cls = lookup(type_name)
    if cls is None:
        raise ConversionError("unknown message type %s" % type_name)
    return cls


# -- ROS -> JSON ---------------------------------------------------------------------------
def message_to_json(msg: genpy.Message) -> Dict[str, Any]:
    """The message as a dict of JSON-ready values (see the module docstring)."""
    return {name: _value_to_json(getattr(msg, name), slot_type)
            for name, slot_type in zip(msg.__slots__, msg._slot_types)}


def _value_to_json(value: Any, slot_type: str) -> Any:
    base, _size = _array(slot_type)
    if base is not None:
        if base in BYTE_ARRAY_BASES:
            raw = value if isinstance(value, (bytes, bytearray)) else bytes(bytearray(value))
            return base64.b64encode(raw).decode("ascii")
        return [_value_to_json(item, base) for item in value]
    if slot_type in TIME_TYPES:
        return {"secs": int(value.secs), "nsecs": int(value.nsecs)}
    if slot_type in FLOAT_TYPES:
        return float(value) if math.isfinite(value) else None
    if slot_type in INT_RANGES:
        return int(value)
    if slot_type == "bool":
        return bool(value)
    if slot_type == "string":
        return value.decode("utf-8", "replace") if isinstance(value, bytes) else value
    return message_to_json(value)


# -- JSON -> ROS ---------------------------------------------------------------------------
def json_to_message(data: Any, cls: Type[genpy.Message], lookup: MessageClassLookup,
                    path: str = "") -> genpy.Message:
    """A `cls` message filled from `data` (a dict; missing fields keep their defaults).
    `lookup` turns a type name such as "geometry_msgs/Vector3" into its class."""
    if not isinstance(data, dict):
        raise ConversionError("%s: expected an object for %s, got %s" % (path or "message", cls._type, _kind(data)))
    slots = dict(zip(cls.__slots__, cls._slot_types))
    unknown = sorted(set(data) - set(slots))
    if unknown:
        raise ConversionError("%s: %s has no field %s" % (path or "message", cls._type, ", ".join(unknown)))
    msg = cls()
    for name, value in data.items():
        setattr(msg, name, _value_from_json(value, slots[name], lookup, _join(path, name)))
    return msg


def _value_from_json(value: Any, slot_type: str, lookup: MessageClassLookup, path: str) -> Any:
    base, size = _array(slot_type)
    if base is not None:
        return _array_from_json(value, base, size, lookup, path)
    if slot_type in TIME_TYPES:
        return _time_from_json(value, TIME_TYPES[slot_type], path)
    if slot_type in FLOAT_TYPES:
        if value is None:
            return math.nan
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ConversionError("%s: expected a number (%s), got %s" % (path, slot_type, _kind(value)))
        return float(value)
    if slot_type in INT_RANGES:
        return _int_from_json(value, slot_type, path)
    if slot_type == "bool":
        if not isinstance(value, bool):
            raise ConversionError("%s: expected true or false, got %s" % (path, _kind(value)))
        return value
    if slot_type == "string":
        if not isinstance(value, str):
            raise ConversionError("%s: expected a string, got %s" % (path, _kind(value)))
        return value
    return json_to_message(value, _message_class(slot_type, lookup), lookup, path)


def _array_from_json(value: Any, base: str, size: Optional[int], lookup: MessageClassLookup, path: str) -> Any:
    if base in BYTE_ARRAY_BASES:
        if isinstance(value, str):
            try:
                items = base64.b64decode(value.encode("ascii"), validate=True)
            except (binascii.Error, UnicodeEncodeError):
                raise ConversionError("%s: expected base64 for %s[], got a string that is not" % (path, base))
        elif isinstance(value, list):
            items = bytes(_int_from_json(item, base, "%s[%d]" % (path, i)) for i, item in enumerate(value))
        else:
            raise ConversionError("%s: expected base64 or a list for %s[], got %s" % (path, base, _kind(value)))
    elif isinstance(value, list):
        items = [_value_from_json(item, base, lookup, "%s[%d]" % (path, i)) for i, item in enumerate(value)]
    else:
        raise ConversionError("%s: expected a list of %s, got %s" % (path, base, _kind(value)))
    if size is not None and len(items) != size:
        raise ConversionError("%s: expected %d items, got %d" % (path, size, len(items)))
    return items


def _int_from_json(value: Any, slot_type: str, path: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ConversionError("%s: expected an integer (%s), got %s" % (path, slot_type, _kind(value)))
    low, high = INT_RANGES[slot_type]
    if not low <= value <= high:
        raise ConversionError("%s: %d is out of range for %s [%d, %d]" % (path, value, slot_type, low, high))
    return value


def _time_from_json(value: Any, cls: type, path: str):
    if not isinstance(value, dict) or set(value) - {"secs", "nsecs"}:
        raise ConversionError("%s: expected {\"secs\", \"nsecs\"}, got %s" % (path, _kind(value)))
    secs = _int_from_json(value.get("secs", 0), "int32" if cls is genpy.Duration else "uint32", path + ".secs")
    nsecs = _int_from_json(value.get("nsecs", 0), "int32" if cls is genpy.Duration else "uint32", path + ".nsecs")
    return cls(secs, nsecs)


def _join(path: str, name: str) -> str:
    return "%s.%s" % (path, name) if path else name


def _kind(value: Any) -> str:
    """How a JSON value is called in an error message."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "the number %r" % value
    if isinstance(value, str):
        return "a string"
    if isinstance(value, list):
        return "a list"
    return "an object"
