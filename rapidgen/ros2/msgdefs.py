"""ROS 2 message definitions: the installed rosidl `.msg` files when there are any, else
a built-in copy of the standard messages the mapping supports.

The installed ones are found as ament does, under `share/<package>/msg/<Type>.msg` of each
AMENT_PREFIX_PATH entry and of this interpreter's prefix (the PyPI ROS wheels put them in
the venv's share/). The built-in table is those files' fields verbatim (comments and
constants dropped), so a descriptor validates the same with or without ROS 2 installed.
"""
from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass
from functools import lru_cache

PRIMITIVES = frozenset({"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16",
                        "int32", "uint32", "int64", "uint64", "string", "wstring"})
INTEGERS = frozenset({"byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"})
FLOATS = frozenset({"float32", "float64"})

BUILTIN: dict[str, str] = {
    "builtin_interfaces/msg/Time": "int32 sec\nuint32 nanosec",
    "std_msgs/msg/Header": "builtin_interfaces/Time stamp\nstring frame_id",
    "std_msgs/msg/String": "string data",
    "std_msgs/msg/Bool": "bool data",
    "std_msgs/msg/Float32": "float32 data",
    "std_msgs/msg/Float64": "float64 data",
    "std_msgs/msg/Int32": "int32 data",
    "std_msgs/msg/Int64": "int64 data",
    "std_msgs/msg/Empty": "",
    "geometry_msgs/msg/Point": "float64 x\nfloat64 y\nfloat64 z",
    "geometry_msgs/msg/Vector3": "float64 x\nfloat64 y\nfloat64 z",
    "geometry_msgs/msg/Quaternion": "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1",
    "geometry_msgs/msg/Pose": "Point position\nQuaternion orientation",
    "geometry_msgs/msg/PoseStamped": "std_msgs/Header header\nPose pose",
    "geometry_msgs/msg/Twist": "Vector3 linear\nVector3 angular",
    "geometry_msgs/msg/TwistStamped": "std_msgs/Header header\nTwist twist",
    "geometry_msgs/msg/Vector3Stamped": "std_msgs/Header header\nVector3 vector",
    "geometry_msgs/msg/Wrench": "Vector3 force\nVector3 torque",
    "geometry_msgs/msg/WrenchStamped": "std_msgs/Header header\nWrench wrench",
    "geometry_msgs/msg/PoseWithCovariance": "Pose pose\nfloat64[36] covariance",
    "geometry_msgs/msg/PoseWithCovarianceStamped": "std_msgs/Header header\nPoseWithCovariance pose",
    "geometry_msgs/msg/TwistWithCovariance": "Twist twist\nfloat64[36] covariance",
    "nav_msgs/msg/Odometry": "std_msgs/Header header\nstring child_frame_id\n"
                             "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist",
    "sensor_msgs/msg/JointState": "std_msgs/Header header\nstring[] name\nfloat64[] position\n"
                                  "float64[] velocity\nfloat64[] effort",
    "sensor_msgs/msg/BatteryState": "std_msgs/Header header\nfloat32 voltage\nfloat32 temperature\n"
                                    "float32 current\nfloat32 charge\nfloat32 capacity\nfloat32 design_capacity\n"
                                    "float32 percentage\nuint8 power_supply_status\nuint8 power_supply_health\n"
                                    "uint8 power_supply_technology\nbool present\nfloat32[] cell_voltage\n"
                                    "float32[] cell_temperature\nstring location\nstring serial_number",
    "sensor_msgs/msg/Image": "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\n"
                             "uint8 is_bigendian\nuint32 step\nuint8[] data",
    "sensor_msgs/msg/CompressedImage": "std_msgs/Header header\nstring format\nuint8[] data",
    "diagnostic_msgs/msg/KeyValue": "string key\nstring value",
    "diagnostic_msgs/msg/DiagnosticStatus": "byte level\nstring name\nstring message\nstring hardware_id\n"
                                            "KeyValue[] values",
    "diagnostic_msgs/msg/DiagnosticArray": "std_msgs/Header header\nDiagnosticStatus[] status",
}

# Services: request and response fields, split by '---' as in a .srv file.
BUILTIN_SRV: dict[str, str] = {
    "std_srvs/srv/Empty": "---",
    "std_srvs/srv/Trigger": "---\nbool success\nstring message",
    "std_srvs/srv/SetBool": "bool data\n---\nbool success\nstring message",
}

# Actions: goal, result and feedback, split by '---' as in a .action file. No standard
# package ships actions as a wheel; test_msgs' Fibonacci (ros-test-msgs) is the example one.
BUILTIN_ACTION: dict[str, str] = {
    "test_msgs/action/Fibonacci": "int32 order\n---\nint32[] sequence\n---\nint32[] sequence",
}

_TYPE_NAME = re.compile(r"^([a-z][a-z0-9_]*)/(?:msg/)?([A-Z][A-Za-z0-9]*)$")
_SRV_NAME = re.compile(r"^([a-z][a-z0-9_]*)/(?:srv/)?([A-Z][A-Za-z0-9]*)$")
_ACTION_NAME = re.compile(r"^([a-z][a-z0-9_]*)/(?:action/)?([A-Z][A-Za-z0-9]*)$")
_FIELD = re.compile(r"^([A-Za-z][A-Za-z0-9_/]*)(?:<=\d+)?(\[(?:<=)?(\d*)\])?\s+([a-z][a-z0-9_]*)(?:\s+.*)?$")


@dataclass(frozen=True)
class Field:
    name: str
    type: str  # a primitive, or a message's full name pkg/msg/Type
    array: bool = False
    size: int | None = None  # fixed array length, None for sequences

    @property
    def primitive(self) -> bool:
        return self.type in PRIMITIVES


@dataclass(frozen=True)
class MsgDef:
    name: str  # pkg/msg/Type
    fields: tuple[Field, ...]
    source: str  # the .msg file, or "built-in"

    def field(self, name: str) -> Field | None:
        return next((f for f in self.fields if f.name == name), None)


def full_name(text: str) -> str | None:
    """'sensor_msgs/JointState' or 'sensor_msgs/msg/JointState' -> 'sensor_msgs/msg/JointState'."""
    m = _TYPE_NAME.match(text)
    return f"{m.group(1)}/msg/{m.group(2)}" if m else None


def full_srv_name(text: str) -> str | None:
    """'std_srvs/Trigger' or 'std_srvs/srv/Trigger' -> 'std_srvs/srv/Trigger'."""
    m = _SRV_NAME.match(text)
    return f"{m.group(1)}/srv/{m.group(2)}" if m else None


def _share_dirs() -> tuple[str, ...]:
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p] + [sys.prefix]
    return tuple(os.path.join(p, "share") for p in prefixes)


def parse(name: str, text: str, source: str) -> MsgDef:
    """A .msg file's fields; constants (`T NAME=value`) are skipped."""
    package = name.split("/", 1)[0]
    fields = []
    for raw in text.splitlines():
        line = raw.split("#", 1)[0].strip()
        if not line or _is_constant(line):
            continue
        m = _FIELD.match(line)
        if m is None:
            continue
        base, arr, size, fname = m.group(1), m.group(2), m.group(3), m.group(4)
        if base == "Header":
            base = "std_msgs/Header"
        if base not in PRIMITIVES:
            base = full_name(base if "/" in base else f"{package}/{base}") or base
        fields.append(Field(fname, base, arr is not None, int(size) if arr and size and "<=" not in arr else None))
    return MsgDef(name, tuple(fields), source)


def _is_constant(line: str) -> bool:
    parts = line.split(None, 1)
    return len(parts) == 2 and re.match(r"^[A-Z][A-Z0-9_]*\s*=", parts[1]) is not None


@lru_cache(maxsize=256)
def lookup(name: str) -> MsgDef | None:
    """The definition of pkg/msg/Type: installed first, else built-in, else None."""
    pkg, _, typ = name.split("/")
    for share in _share_dirs():
        path = os.path.join(share, pkg, "msg", typ + ".msg")
        if os.path.isfile(path):
            try:
                with open(path, encoding="utf-8") as f:
                    return parse(name, f.read(), path)
            except (OSError, UnicodeDecodeError):
                break
    text = BUILTIN.get(name)
    return None if text is None else parse(name, text, "built-in")


def full_action_name(text: str) -> str | None:
    """'test_msgs/Fibonacci' or 'test_msgs/action/Fibonacci' -> 'test_msgs/action/Fibonacci'."""
    m = _ACTION_NAME.match(text)
    return f"{m.group(1)}/action/{m.group(2)}" if m else None


def _parts(name: str, kind: str, builtin: dict[str, str], roles: tuple[str, ...]) -> tuple[MsgDef, ...] | None:
    """The '---'-separated parts of a .srv or .action file: installed first, else built-in."""
    pkg, _, typ = name.split("/")
    text, source = builtin.get(name), "built-in"
    for share in _share_dirs():
        path = os.path.join(share, pkg, kind, f"{typ}.{kind}")
        if os.path.isfile(path):
            try:
                with open(path, encoding="utf-8") as f:
                    text, source = f.read(), path
            except (OSError, UnicodeDecodeError):
                pass
            break
    if text is None:
        return None
    chunks: list[list[str]] = [[]]
    for line in text.splitlines():
        if line.strip() == "---":
            chunks.append([])
        else:
            chunks[-1].append(line)
    chunks += [[] for _ in range(len(roles) - len(chunks))]
    return tuple(parse(f"{name} {role}", "\n".join(chunk), source) for role, chunk in zip(roles, chunks))


@lru_cache(maxsize=64)
def lookup_srv(name: str) -> tuple[MsgDef, MsgDef] | None:
    """(request, response) of pkg/srv/Type."""
    found = _parts(name, "srv", BUILTIN_SRV, ("request", "response"))
    return None if found is None else (found[0], found[1])


@lru_cache(maxsize=64)
def lookup_action(name: str) -> tuple[MsgDef, MsgDef, MsgDef] | None:
    """(goal, result, feedback) of pkg/action/Type."""
    found = _parts(name, "action", BUILTIN_ACTION, ("goal", "result", "feedback"))
    return None if found is None else (found[0], found[1], found[2])


def resolve_path(msg: MsgDef, path: str) -> tuple[Field | None, str | None]:
    """The field at a dotted path (`pose.pose.position`, `position[2]`), or (None, why)."""
    current: MsgDef | None = msg
    field: Field | None = None
    for part in path.split("."):
        m = re.match(r"^([a-z][a-z0-9_]*)(?:\[(\d+)\])?$", part)
        if m is None:
            return None, f"'{part}' is not a field name (lower-case letters, digits, _; an index as [2])"
        if current is None:
            return None, f"'{field.name if field else ''}' is a {field.type if field else '?'}, it has no fields"
        found = current.field(m.group(1))
        if found is None:
            names = ", ".join(f.name for f in current.fields) or "none"
            return None, f"no '{m.group(1)}' in {current.name}; its fields: {names}"
        if m.group(2) is not None:
            if not found.array:
                return None, f"'{found.name}' is not an array"
            index = int(m.group(2))
            if found.size is not None and index >= found.size:
                return None, f"'{found.name}' holds {found.size} elements"
            found = Field(found.name, found.type)  # the element
        field = found
        current = None if found.primitive or found.array else lookup(found.type)
        if not found.primitive and not found.array and current is None:
            return None, f"unknown message type {found.type}"
    return field, None
