"""RAPID samples as Foxglove's well-known messages (docs/foxglove.md), shared by `rapidgen record
--foxglove` and the live Foxglove server: each decoded RAPID sample gives zero or more derived
messages, JSON objects valid against the schemas of rapidgen.foxglove.schemas.

- PositionSample -> foxglove.FrameTransform (parent: the PositionConfig's frameName, else the
  descriptor's `frame`; child: the asset's partition name, PARTITION/SUFFIX for a suffixed
  topic) and foxglove.PoseInFrame (in that
  frame). The rotation is read per the PositionConfig's poseEncoding (else the descriptor's
  pose_encoding): QUAT (x, y, z, w), M33 (row-major; not a rotation, e.g. all zeros: identity),
  Euler XYZ/ZYX/ZYZ; NONE or unknown gives the identity.
- any sample with numeric `latitude` and `longitude` (K10's rapid::ext::arc::GpsSample) ->
  foxglove.LocationFix (`altitude` if present; covariance unknown).
- ImageSensorSample -> foxglove.CompressedImage (image/jpeg, png, webp, avif) or
  foxglove.RawImage (image/x-gray8 as mono8, image/x-rgb8 as rgb8); frame: the sensor's name.
- TextMessage -> foxglove.Log (name "Asset/category", RAPID levels mapped).
- JointSample -> foxglove.JointStates, only once a JointConfig of the same topic suffix
  names the joints (its jointDefinitions' frameName).

Stamps are the samples' own (Header.timeStamp, microseconds); a negative one is replaced by
the time the sample was received.
"""
from __future__ import annotations

import base64
import enum
import math
from dataclasses import dataclass
from typing import Any

from rapid_runtime.ros2.rotations import quat_from_euler, quat_from_m33

# rapid::MessageLevel -> foxglove.LogLevel (DEBUG 1, INFO 2, WARNING 3, ERROR 4, FATAL 5)
LOG_LEVELS = {"MSG_DEBUG": 1, "MSG_INFO": 2, "MSG_ATTENTION": 3, "MSG_WARN": 3, "MSG_ERROR": 4, "MSG_CRITICAL": 5}
COMPRESSED = {"jpeg": "jpeg", "jpg": "jpeg", "pjpeg": "jpeg", "png": "png", "webp": "webp", "avif": "avif"}
RAW = {"x-gray8": ("mono8", 1), "x-rgb8": ("rgb8", 3)}
IDENTITY = (0.0, 0.0, 0.0, 1.0)


@dataclass(frozen=True)
class Derived:
    """One derived message: its channel's topic, Foxglove schema name and the message (JSON)."""
    topic: str
    schema: str
    message: dict[str, Any]
    source: str  # the RAPID topic it came from


def derived_topic(partition: str, rapid_topic: str, what: str) -> str:
    """/PARTITION/RAPID_TOPIC/WHAT: one channel per asset, RAPID topic and derived kind."""
    return f"/{partition}/{rapid_topic}/{what}"


def _name(value: Any) -> str:
    return value.name if isinstance(value, enum.Enum) else str(value)


def _f(x: Any) -> float:
    v = float(x)
    return v if math.isfinite(v) else 0.0


def stamp(micros: Any, received_ns: int) -> dict[str, int]:
    """foxglove.Time of a RAPID timestamp (microseconds since 1970), else of the receive time."""
    try:
        us = int(micros)
    except (TypeError, ValueError):
        us = -1
    ns = us * 1000 if us >= 0 else max(0, received_ns)
    return {"sec": min(ns // 1_000_000_000, 2**32 - 1), "nsec": ns % 1_000_000_000}


def is_rotation(m: list[float], tol: float = 1e-3) -> bool:
    """A row-major 3x3 that is orthonormal with determinant +1 (float32 rounding allowed)."""
    if len(m) < 9 or not all(math.isfinite(v) for v in m[:9]):
        return False
    rows = [m[0:3], m[3:6], m[6:9]]
    for i in range(3):
        for j in range(3):
            dot = sum(rows[i][k] * rows[j][k] for k in range(3))
            if abs(dot - (1.0 if i == j else 0.0)) > tol:
                return False
    (a, b, c), (d, e, f), (g, h, i2) = rows
    return abs(a * (e * i2 - f * h) - b * (d * i2 - f * g) + c * (d * h - e * g) - 1.0) <= tol


def rotation(encoding: str, rot: list[float]) -> tuple[float, float, float, float]:
    """A RAPID Transform3D.rot as a unit quaternion (x, y, z, w), per RotationEncoding."""
    if encoding == "RAPID_ROT_QUAT":
        q = tuple(rot[:4])
    elif encoding == "RAPID_ROT_M33":
        if not is_rotation(rot):
            return IDENTITY  # (a zero matrix: no pose filled in)
        q = quat_from_m33(rot[:9])
    elif encoding in ("RAPID_ROT_XYZ", "RAPID_ROT_ZYX", "RAPID_ROT_ZYZ"):
        axes = encoding.rsplit("_", 1)[1]  # intrinsic rotations in this order
        q = quat_from_euler(rot[:3], axes)
    else:
        return IDENTITY
    n = math.sqrt(sum(c * c for c in q))
    if not math.isfinite(n) or n < 1e-12:
        return IDENTITY
    x, y, z, w = (c / n for c in q)
    return (x, y, z, w)


def _suffix(topic: str) -> str:
    return topic.partition("-")[2]


def child_frame(partition: str, topic: str) -> str:
    """The frame a PositionSample places: the asset (its partition), or PARTITION/SUFFIX for a
    suffixed topic (Robonaut 2's rapid_position_sample-leftArm: Robonaut2/leftArm)."""
    suffix = _suffix(topic)
    return f"{partition}/{suffix}" if suffix else partition


class Deriver:
    """Derives messages from a stream of decoded RAPID samples, remembering each asset's
    PositionConfig and JointConfig. `frames`: (partition, PositionSample topic) -> (frame, pose
    encoding) from the descriptors (used until that topic's PositionConfig is seen)."""

    MAX_KEYS = 4096  # remembered configs (a hostile domain cannot grow them without bound)

    def __init__(self, frames: dict[tuple[str, str], tuple[str, str]] | None = None) -> None:
        self.frames = dict(frames or {})
        self._position: dict[tuple[str, str], tuple[str, str]] = {}  # (partition, suffix) -> (frame, encoding)
        self._joints: dict[tuple[str, str], list[str]] = {}  # (partition, suffix) -> joint names

    def _remember(self, table: dict, key: tuple[str, str], value: Any) -> None:
        if key in table or len(table) < self.MAX_KEYS:
            table[key] = value

    def feed(self, topic: str, partition: str, type_name: str, sample: Any, received_ns: int) -> list[Derived]:
        """The derived messages of one decoded RAPID sample (none for most types)."""
        short = type_name.replace(".", "::").rpartition("::")[2]
        try:
            if short == "PositionConfig":
                self._remember(self._position, (partition, _suffix(topic)),
                               (str(sample.frameName), _name(sample.poseEncoding)))
                return []
            if short == "JointConfig":
                self._remember(self._joints, (partition, _suffix(topic)),
                               [str(d.frameName) for d in sample.jointDefinitions])
                return []
            if short == "PositionSample":
                return self._pose(topic, partition, sample, received_ns)
            if short == "ImageSensorSample":
                return self._image(topic, partition, sample, received_ns)
            if short == "TextMessage":
                return self._log(topic, partition, sample, received_ns)
            if short == "JointSample":
                return self._joint(topic, partition, sample, received_ns)
            if isinstance(getattr(sample, "latitude", None), (int, float)) and \
                    isinstance(getattr(sample, "longitude", None), (int, float)):
                return self._fix(topic, partition, sample, received_ns)
        except (AttributeError, TypeError, ValueError, IndexError, OverflowError):
            return []  # a sample of another shape under a RAPID name: nothing derived
        return []

    def _pose(self, topic: str, partition: str, s: Any, received_ns: int) -> list[Derived]:
        known = self._position.get((partition, _suffix(topic)))
        frame, encoding = known if known is not None else self.frames.get((partition, topic), ("", ""))
        if not frame:
            return []  # no PositionConfig yet and no descriptor frame: which frame is unknown
        t = stamp(s.hdr.timeStamp, received_ns)
        xyz = {"x": _f(s.pose.xyz[0]), "y": _f(s.pose.xyz[1]), "z": _f(s.pose.xyz[2])}
        x, y, z, w = rotation(encoding, [_f(v) for v in s.pose.rot])
        q = {"x": x, "y": y, "z": z, "w": w}
        return [Derived(derived_topic(partition, topic, "transform"), "foxglove.FrameTransform",
                        {"timestamp": t, "parent_frame_id": frame, "child_frame_id": child_frame(partition, topic),
                         "translation": xyz, "rotation": q}, topic),
                Derived(derived_topic(partition, topic, "pose"), "foxglove.PoseInFrame",
                        {"timestamp": t, "frame_id": frame, "pose": {"position": dict(xyz), "orientation": dict(q)}},
                        topic)]

    def _fix(self, topic: str, partition: str, s: Any, received_ns: int) -> list[Derived]:
        hdr = getattr(s, "hdr", None)
        alt = getattr(s, "altitude", 0.0)
        return [Derived(derived_topic(partition, topic, "location"), "foxglove.LocationFix",
                        {"timestamp": stamp(getattr(hdr, "timeStamp", -1), received_ns), "frame_id": partition,
                         "latitude": _f(s.latitude), "longitude": _f(s.longitude),
                         "altitude": _f(alt) if isinstance(alt, (int, float)) else 0.0,
                         "position_covariance": [0.0] * 9, "position_covariance_type": 0}, topic)]

    def _image(self, topic: str, partition: str, s: Any, received_ns: int) -> list[Derived]:
        sub = str(s.mimeType).split("/", 1)[-1].strip().lower()
        data = bytes(s.data)
        t = stamp(s.hdr.timeStamp, received_ns)
        frame = str(s.meta.sensorName) or partition
        if sub in COMPRESSED:
            return [Derived(derived_topic(partition, topic, "image"), "foxglove.CompressedImage",
                            {"timestamp": t, "frame_id": frame, "format": COMPRESSED[sub],
                             "data": base64.b64encode(data).decode("ascii")}, topic)]
        if sub in RAW:
            encoding, channels = RAW[sub]
            width, height = int(s.meta.width), int(s.meta.height)
            if width <= 0 or height <= 0 or width * height * channels != len(data):
                return []  # the bytes are not the picture the metadata says
            return [Derived(derived_topic(partition, topic, "image"), "foxglove.RawImage",
                            {"timestamp": t, "frame_id": frame, "width": width, "height": height,
                             "encoding": encoding, "step": width * channels,
                             "data": base64.b64encode(data).decode("ascii")}, topic)]
        return []

    def _log(self, topic: str, partition: str, s: Any, received_ns: int) -> list[Derived]:
        category = str(s.category)
        asset = str(s.hdr.assetName) or partition
        return [Derived(derived_topic(partition, topic, "log"), "foxglove.Log",
                        {"timestamp": stamp(s.hdr.timeStamp, received_ns), "level": LOG_LEVELS.get(_name(s.level), 0),
                         "message": str(s.message), "name": f"{asset}/{category}" if category else asset,
                         "file": "", "line": 0}, topic)]

    def _joint(self, topic: str, partition: str, s: Any, received_ns: int) -> list[Derived]:
        names = self._joints.get((partition, _suffix(topic)))
        if not names:
            return []
        cols = {"position": list(s.anglePos), "velocity": list(s.angleVel), "effort": list(s.torque)}
        joints = []
        for i, name in enumerate(names):
            j: dict[str, Any] = {"name": name}
            for key, values in cols.items():
                if len(values) == len(names):
                    j[key] = _f(values[i])
            joints.append(j)
        return [Derived(derived_topic(partition, topic, "joints"), "foxglove.JointStates",
                        {"timestamp": stamp(s.hdr.timeStamp, received_ns), "joints": joints}, topic)]
