"""ROS 2 messages by name and by field path, and command arguments turned into field values
(the conversions ros2_map.COMMANDS names). Needs rclpy's message packages only to look a
class up (message_class); the rest works on any object with the fields."""
from __future__ import annotations

import importlib
from typing import Any, Sequence

from rapid_runtime.handlers import CommandFailed
from rapid_runtime.ros2.rotations import quat_from_m33, quat_from_rpy


def describe(msg: Any) -> str:
    """A message's fields as short text for an ack: 'sequence=[0, 1, 1]'."""
    parts = []
    for name in msg.get_fields_and_field_types():
        value = getattr(msg, name)
        value = list(value) if hasattr(value, "__len__") and not isinstance(value, str) else value
        parts.append(f"{name}={value}")
    return ", ".join(parts)


def message_class(name: str) -> Any:
    """'sensor_msgs/msg/JointState' -> the rclpy message class."""
    package, kind, type_name = name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), type_name)


def get_field(msg: Any, path: str) -> Any:
    """The value at a dotted field path ('pose.position', 'position[2]'; '' is msg)."""
    for part in path.split(".") if path else ():
        name, _, index = part.partition("[")
        msg = getattr(msg, name)
        if index:
            msg = msg[int(index[:-1])]
    return msg


def set_field(msg: Any, path: str, value: Any) -> None:
    parent, _, last = path.rpartition(".")
    target = get_field(msg, parent)
    name, _, index = last.partition("[")
    if index:
        getattr(target, name)[int(index[:-1])] = value
    else:
        setattr(target, name, value)


def argument(args: Sequence[Any], ref: Any) -> Any:
    """One reference's value: a parameter's index (the argument as it is) or [index, element
    (None: all of it), scale] (`xyt[2]`, {from: xyz, scale: 0.001})."""
    if isinstance(ref, int):
        return args[ref]
    index, element, scale = ref
    value = args[index] if element is None else args[index][element]
    if scale == 1:
        return value
    if isinstance(value, (list, tuple)):
        return [float(x) * scale for x in value]
    return float(value) * scale


def field_value(conv: str, source: Any, args: Sequence[Any], current: Any) -> Any:
    """The value a field gets: a constant, or the arguments the references in `source` name."""
    if conv == "const":
        return source
    if conv == "quat_euler":  # {roll, pitch, yaw}: one number each, 0 when left out
        r, p, y = (0.0 if ref is None else float(argument(args, ref)) for ref in source)
        current.x, current.y, current.z, current.w = quat_from_rpy(r, p, y)
        return current
    vals = [argument(args, ref) for ref in source]
    if conv == "float":
        return float(vals[0])
    if conv == "int":
        return int(vals[0])
    if conv == "bool":
        return bool(vals[0])
    if conv == "str":
        return str(vals[0])
    if conv == "list":
        return [float(x) for v in vals for x in (v if isinstance(v, (list, tuple)) else [v])]
    if conv == "vec3":
        current.x, current.y, current.z = (float(x) for x in vals[0])
        return current
    if conv in ("quat_rpy", "quat_m33"):
        if conv == "quat_rpy":
            r, p, y = (float(x) for x in vals[0])
            q = quat_from_rpy(r, p, y)
        else:
            q = quat_from_m33(vals[0])
        current.x, current.y, current.z, current.w = q
        return current
    raise CommandFailed(f"unknown conversion {conv}")
