"""The descriptor's `ros2:` section: read, checked against the asset and the ROS 2 message
definitions, and turned into the plain data `<pkg>/ros2_map.py` carries.

Every problem is located at the YAML key or value it concerns (RG1501-RG1506). The
section is checked by hand rather than by the JSON Schema so that a field path or a
parameter name can be judged against the message and the command it belongs to.
"""
from __future__ import annotations

import math
import re
from typing import Any

from rapidgen.yamlread import YamlDoc
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.ros2 import msgdefs
from rapidgen.ros2.msgdefs import FLOATS, INTEGERS, Field

_TOPIC = re.compile(r"^/?[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*$")
_NODE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]{0,63}$")
NUMERIC = ("RAPID_DOUBLE", "RAPID_FLOAT", "RAPID_INT", "RAPID_LONGLONG")
VEC3_MSGS = ("geometry_msgs/msg/Point", "geometry_msgs/msg/Vector3")
QUAT = "geometry_msgs/msg/Quaternion"
# Where a pose (and a velocity) sits in the messages a position entry may be fed from.
POSE_SOURCES = {
    "geometry_msgs/msg/PoseStamped": ("pose", None),
    "geometry_msgs/msg/Pose": ("", None),
    "nav_msgs/msg/Odometry": ("pose.pose", "twist.twist"),
    "geometry_msgs/msg/PoseWithCovariance": ("pose", None),
}
JOINT_SOURCE = "sensor_msgs/msg/JointState"
BATTERY = "sensor_msgs/msg/BatteryState"  # its percentage is 0-1 (REP 145 / the message's comment)
PERCENT = ("%", "percent", "pct")
# What an image entry's declared MIME type must be for each image message: a compressed
# image is passed on as it is; a raw one is wrapped as PNM (rgb8/bgr8 -> PPM, mono8 -> PGM).
IMAGE_SOURCES = {"sensor_msgs/msg/CompressedImage": ("image/jpeg", "image/png"),
                 "sensor_msgs/msg/Image": ("image/x-portable-pixmap", "image/x-portable-graymap")}
# Euler XYZ/ZYX (intrinsic, radians; ZYX: heading first) from the quaternion too; ZYZ is not made
# (undefined at the identity a rover mostly stands in).
ENCODINGS = ("RAPID_ROT_QUAT", "RAPID_ROT_M33", "RAPID_ROT_XYZ", "RAPID_ROT_ZYX", "RAPID_ROT_NONE")
VELOCITY_ENCODINGS = ("RAPID_ROT_NONE", "RAPID_ROT_VEL")

_SECTION_KEYS = ("node", "telemetry", "commands", "streams", "ground")
_GROUND_KEYS = ("namespace", "diagnostics", "node")
_FEED_KEYS = ("topic", "type", "feeds", "index", "joints", "values", "description")
_COMMAND_KEYS = ("command", "publish", "call", "action", "until", "cancel", "description")
_CALL_KEYS = ("service", "type", "fields", "timeout")
_ACTION_KEYS = ("action", "type", "fields", "timeout")
_DOINGS = ("publish", "call", "action")  # what a command does; exactly one
_PUBLISH_KEYS = ("topic", "type", "fields")
_UNTIL_KEYS = ("topic", "type", "field", "equals", "timeout")
_STREAM_KEYS = ("stream", "topic", "type", "frame", "pose_encoding", "joints", "stop", "description")
# What each RAPID stream sample may become in ROS 2: the pose's place in the message, or joints.
STREAM_TARGETS: dict[str, dict[str, str | None]] = {
    "rapid::PositionSample": {"geometry_msgs/msg/PoseStamped": "pose", "geometry_msgs/msg/Pose": ""},
    "rapid::JointSample": {JOINT_SOURCE: None}}
STREAM_ENCODINGS = ("RAPID_ROT_QUAT", "RAPID_ROT_M33")
# Command arguments -> fields: name[i] picks one element of a vector parameter; roll/pitch/yaw
# build a quaternion from single numbers (simpleMove's heading: {yaw: xyt[2]}).
_ELEMENT = re.compile(r"^(.+)\[(\d+)\]$")
ELEMENTS = {"RAPID_VEC3d": 3, "RAPID_MAT33f": 9}
EULER = ("roll", "pitch", "yaw")
SCALABLE = ("float", "list", "vec3", "quat_rpy", "quat_euler")
ANGLE_UNITS = ("rad", "deg", "radian", "radians", "degree", "degrees")
# Standard commands the runtime answers without a handler (docs/runtime.md), so without a
# mapping too; stopAllMotion cancels the Mobility commands (and their `cancel` messages).
RUNTIME_ANSWERS = frozenset({("Admin", "echo"), ("Admin", "noOp"), ("Admin", "shutdown"), ("Queue", "cancelAll"),
                             ("AccessControl", "requestControl"), ("AccessControl", "grabControl"),
                             ("AccessControl", "releaseControl"), ("AccessControl", "transferControl"),
                             ("Mobility", "stopAllMotion")})


class _NoParameters:
    """A stream's stop message has no command arguments: constants only."""
    parameters: tuple = ()


class _Reader:
    def __init__(self, doc: YamlDoc, loaded: Any, sink: DiagnosticSink) -> None:
        self.doc, self.loaded, self.sink = doc, loaded, sink
        self.ok = True

    # -- reporting -----------------------------------------------------------------------
    def error(self, code: str, message: str, path: tuple, hint: str, key: bool = False) -> None:
        loc = self.doc.key_loc(path) if key else self.doc.loc(path)
        self.sink.error(code, message, loc, hint)
        self.ok = False

    def mapping(self, value: object, path: tuple, keys: tuple[str, ...], required: tuple[str, ...]) -> bool:
        if not isinstance(value, dict):
            self.error("RG1505", f"'{'.'.join(map(str, path))}' must be a mapping", path,
                       f"keys: {', '.join(keys)}")
            return False
        good = True
        for k in value:
            if k not in keys:
                self.error("RG1505", f"unknown key '{k}'", path + (k,), f"keys here: {', '.join(keys)}", key=True)
                good = False
        for k in required:
            if k not in value:
                self.error("RG1505", f"missing key '{k}'", path, f"add '{k}:'")
                good = False
        return good

    def text(self, value: object, path: tuple, what: str) -> str | None:
        if not isinstance(value, str) or not value:
            self.error("RG1505", f"{what} must be text", path, "quote it")
            return None
        return value

    def topic(self, value: object, path: tuple) -> str | None:
        t = self.text(value, path, "a topic")
        if t is not None and not _TOPIC.match(t):
            self.error("RG1505", f"'{t}' is not a ROS 2 topic name", path,
                       "letters, digits and _ in /-separated tokens, each starting with a letter or _")
            return None
        return t

    def msg_type(self, value: object, path: tuple) -> msgdefs.MsgDef | None:
        t = self.text(value, path, "a message type")
        if t is None:
            return None
        name = msgdefs.full_name(t)
        if name is None:
            self.error("RG1501", f"'{t}' is not a ROS 2 message type name", path,
                       "write package/msg/Type, e.g. sensor_msgs/msg/JointState")
            return None
        found = msgdefs.lookup(name)
        if found is None:
            self.error("RG1501", f"unknown ROS 2 message type {name}", path,
                       "not installed (no share/<package>/msg/<Type>.msg on AMENT_PREFIX_PATH or in this "
                       f"Python's prefix) and not one of the {len(msgdefs.BUILTIN)} built in (docs/ros2.md)")
        return found

    def field(self, msg: msgdefs.MsgDef, path_text: object, path: tuple, key: bool = False) -> Field | None:
        if not isinstance(path_text, str) or not path_text:
            self.error("RG1505", "a field path must be text", path, "write e.g. pose.position", key)
            return None
        found, why = msgdefs.resolve_path(msg, path_text)
        if found is None:
            self.error("RG1502", f"{msg.name} has no field '{path_text}'", path, why or "", key)
        return found

    # -- the section ---------------------------------------------------------------------
    def read(self, section: object) -> dict | None:
        root = ("ros2",)
        if not self.mapping(section, root, _SECTION_KEYS, ()):
            return None
        assert isinstance(section, dict)
        node = section.get("node", "rapid_" + re.sub(r"[^A-Za-z0-9_]", "_", self.loaded.spec.name).lower())
        if "node" in section and (not isinstance(node, str) or not _NODE.match(node)):
            self.error("RG1505", f"'{node}' is not a ROS 2 node name", root + ("node",),
                       "letters, digits and _, starting with a letter or _ (at most 64)")
        feeds = self.items(section.get("telemetry", []), root + ("telemetry",), self.feed)
        commands = self.items(section.get("commands", []), root + ("commands",), self.command)
        self.duplicates(feeds, commands)
        streams = self.items(section.get("streams", []), root + ("streams",), self.stream)
        seen: dict[str, tuple] = {}
        for st, p in streams:
            if st["stream"] in seen:
                self.error("RG1506", f"stream '{st['stream']}' is mapped twice", p + ("stream",),
                           f"first mapped at line {self.doc.loc(seen[st['stream']]).line}")
            seen.setdefault(st["stream"], p + ("stream",))
        commands_by_name = {c["command"]: c for c, _ in commands}
        for st, _p in streams:  # on_loss stop without a stop message: a mapped cancel of the stream's subsystem
            if st["on_loss"] == "stop" and st["stop"] is None and st["subsystem"]:
                st["stop"] = next((c["cancel"] for name, c in commands_by_name.items()
                                   if name.startswith(st["subsystem"] + "/") and c.get("cancel") is not None
                                   and all(f[1] == "const" for f in c["cancel"]["fields"])), None)
        if self.ok and ("telemetry" in section or "commands" in section):  # errors first
            self.unfed({(f["feeds"], f["index"]) for f, _ in feeds})
            self.unmapped({c["command"] for c, _ in commands})
        ground = self.ground(section["ground"], root + ("ground",), node) if "ground" in section else None
        if not self.ok:
            return None
        return {"node": node, "telemetry": [f for f, _ in feeds],
                "commands": {c["command"]: c for c, _ in commands}, "streams": [st for st, _ in streams],
                "ground": ground}

    # -- streams: a RAPID input stream (Cyclone, DEADLINE) -> ROS 2 messages --------------
    def stream(self, item: object, path: tuple) -> dict | None:
        """An input stream of the descriptor (streams:) whose samples become ROS 2 messages."""
        if not self.mapping(item, path, _STREAM_KEYS, ("stream", "topic", "type")):
            return None
        assert isinstance(item, dict)
        name = self.text(item["stream"], path + ("stream",), "a stream name")
        topic = self.topic(item["topic"], path + ("topic",))
        msg = self.msg_type(item["type"], path + ("type",))
        if name is None:
            return None
        inputs = {s.name: s for s in self.loaded.streams if s.direction == "input"}
        found = inputs.get(name)
        if found is None:
            output = any(s.name == name for s in self.loaded.streams)
            self.error("RG1504", f"'{name}' is {'an output' if output else 'no input'} stream of the asset",
                       path + ("stream",), "the bridge reads the descriptor's input streams: "
                       + (", ".join(inputs) or "it declares none (add one under streams:)"))
            return None
        targets = STREAM_TARGETS.get(found.type)
        if targets is None:
            self.error("RG1503", f"stream '{name}' carries {found.type}, which the ROS 2 bridge cannot map",
                       path + ("stream",), "streams of rapid::PositionSample or rapid::JointSample map to ROS 2")
            return None
        if topic is None or msg is None:
            return None
        if msg.name not in targets:
            self.error("RG1503", f"{found.type} (stream '{name}') cannot become {msg.name}", path + ("type",),
                       "map it to " + " or ".join(targets))
            return None
        joints = found.type == "rapid::JointSample"
        for k in ("frame", "pose_encoding") if joints else ("joints",):
            if k in item:
                self.error("RG1505", f"'{k}' is for {'PositionSample' if joints else 'JointSample'} streams",
                           path + (k,), "leave it out")
        out: dict[str, Any] = {"stream": name, "type": found.type, "topic": found.topic,
                               "partition": found.partition, "deadline_ms": found.deadline_ms,
                               "on_loss": found.on_loss, "subsystem": found.subsystem,
                               "state_key": found.state_key, "missed_key": found.missed_key,
                               "ros2": {"topic": topic, "type": msg.name, "pose": targets[msg.name],
                                        "stamp": msg.name.endswith("Stamped") or joints}}
        if joints:
            names = item.get("joints", [])
            if not isinstance(names, list) or not all(isinstance(n, str) and n for n in names):
                self.error("RG1505", "'joints' must be a list of ROS 2 joint names", path + ("joints",),
                           "one name per joint of the stream's samples, in their order")
                return None
            out["ros2"]["joints"] = list(names)
        else:
            frame = item.get("frame", "")
            if not isinstance(frame, str):
                self.error("RG1505", "'frame' must be text", path + ("frame",), "the header's frame_id")
                return None
            encoding = item.get("pose_encoding", "RAPID_ROT_QUAT")
            if encoding not in STREAM_ENCODINGS:
                self.error("RG1503", f"a stream pose in {encoding!r} cannot become a ROS 2 quaternion",
                           path + ("pose_encoding",), "the writer's rot encoding: " + " or ".join(STREAM_ENCODINGS))
                return None
            out["ros2"].update(frame=frame, encoding=encoding)
        out["stop"] = None
        if "stop" in item:
            if found.on_loss != "stop":
                self.error("RG1505", f"stream '{name}' has on_loss: {found.on_loss}, so nothing is stopped",
                           path + ("stop",), "set 'on_loss: stop' on the stream, or leave 'stop' out")
                return None
            out["stop"] = self.publish(item["stop"], path + ("stop",), _NoParameters())
            if out["stop"] is None:
                return None
        return out

    # -- the ground side: RAPID telemetry -> ROS 2 topics --------------------------------
    def ground(self, value: object, path: tuple, node: str) -> dict | None:
        """Which ROS 2 topics the asset's joint, position, agent, image and text telemetry goes to."""
        if value is True:
            value = {}
        if not self.mapping(value, path, _GROUND_KEYS, ()):
            return None
        assert isinstance(value, dict)
        base = "/" + re.sub(r"[^A-Za-z0-9_]", "_", self.loaded.spec.name).lower()
        ns = self.topic(value.get("namespace", base), path + ("namespace",)) if "namespace" in value else base
        diagnostics = self.topic(value.get("diagnostics", "/diagnostics"), path + ("diagnostics",))
        gnode = value.get("node", node + "_ground")
        if not isinstance(gnode, str) or not _NODE.match(gnode):
            self.error("RG1505", f"'{gnode}' is not a ROS 2 node name", path + ("node",),
                       "letters, digits and _, starting with a letter or _ (at most 64)")
        if ns is None or diagnostics is None:
            return None
        ns = ns.rstrip("/") if ns != "/" else ""
        entries = []
        counts: dict[str, int] = {}
        for t in self.loaded.spec.telemetry:
            if t.kind not in ("joint", "position", "agent", "image", "text"):
                continue
            index = counts.get(t.kind, 0)
            counts[t.kind] = index + 1
            sub = "/" + re.sub(r"[^A-Za-z0-9_]", "_", t.suffix) if t.suffix else ""
            if t.kind == "joint":
                entries.append({"kind": "joint", "index": index, "topic": f"{ns}{sub}/joint_states",
                                "names": [j.frame for j in t.joints]})
            elif t.kind == "position":
                entries.append({"kind": "position", "index": index, "topic": f"{ns}{sub}/pose", "frame": t.frame,
                                "encoding": t.pose_encoding})
            elif t.kind == "image":
                entries.append({"kind": "image", "index": index, "topic": f"{ns}{sub}/image/compressed"})
            elif t.kind == "text":
                entries.append({"kind": "text", "index": index, "topic": "/rosout"})
            else:
                entries.append({"kind": "agent", "index": index, "topic": diagnostics,
                                "values": [[v.name, v.type, v.unit or "", _levels(v.warning), _levels(v.critical)]
                                           for v in t.values]})
        return {"node": gnode, "namespace": ns, "entries": entries}

    def unfed(self, fed: set[tuple[str, int]]) -> None:
        """Warn of telemetry the ROS 2 bridge will never publish (conform's TEL-01 would fail)."""
        counts: dict[str, int] = {}
        for t in self.loaded.spec.telemetry:
            index = counts.get(t.kind, 0)
            counts[t.kind] = index + 1
            if (t.kind, index) in fed or t.kind == "text":  # text: the bridge's start-up line
                continue
            if t.kind in ("joint", "position", "agent", "image"):
                hint = f"feed it: add '- {{topic: ..., type: ..., feeds: {t.kind}" + \
                    (f", index: {index}" if index else "") + "}' under ros2.telemetry"
            else:
                hint = "the ROS 2 bridge feeds joint, position, agent and image entries (and writes one text line)"
            self.sink.warning("RG1507", f"no ROS 2 topic feeds {t.kind} telemetry entry {index}: the ROS 2 bridge "
                              "never publishes it", t.loc, hint)

    def unmapped(self, mapped: set[str]) -> None:
        """Warn of advertised commands the ROS 2 bridge would answer EXEC_FAILED "... has no ROS 2
        mapping": every command but those the runtime answers itself (RUNTIME_ANSWERS)."""
        for sub in self.loaded.subsystems:
            t = self.loaded.types.get(sub.type)
            for c in (t.commands if t else ()):
                name = f"{sub.name}/{c.name}"
                if name in mapped or (t is not None and t.standard and (sub.type, c.name) in RUNTIME_ANSWERS):
                    continue
                # a standard type's commands are not written in the descriptor: its subsystem entry is
                loc = sub.loc if t is None or t.standard else c.loc
                self.sink.warning("RG1508", f"command {name} has no ROS 2 mapping: the ROS 2 bridge answers it "
                                  "EXEC_FAILED", loc,
                                  f"map it: add '- {{command: {name}, publish: {{topic: ..., type: ..., "
                                  "fields: ...}}' (or call:/action:) under ros2.commands, or leave the command out")

    def items(self, value: object, path: tuple, read) -> list[tuple[dict, tuple]]:
        if not isinstance(value, list):
            self.error("RG1505", f"'{path[-1]}' must be a list", path, "one '- ' item per mapping")
            return []
        out = []
        for i, item in enumerate(value):
            got = read(item, path + (i,))
            if got is not None:
                out.append((got, path + (i,)))
        return out

    def duplicates(self, feeds: list[tuple[dict, tuple]], commands: list[tuple[dict, tuple]]) -> None:
        seen: dict[object, tuple] = {}
        for f, p in feeds:  # an agent entry may take its values from several topics, each value from one
            keys = [(f["index"], v[0]) for v in f["values"]] if f["feeds"] == "agent" else [(f["feeds"], f["index"])]
            for k in keys:
                if k in seen:
                    what = f"agent value '{k[1]}'" if f["feeds"] == "agent" else \
                        f"{f['feeds']} telemetry entry {f['index']}"
                    self.error("RG1506", f"{what} is fed twice", p, f"first fed at line {self.doc.loc(seen[k]).line}")
                seen.setdefault(k, p)
        for c, p in commands:
            k = c["command"]
            if k in seen:
                self.error("RG1506", f"command '{k}' is mapped twice", p + ("command",),
                           f"first mapped at line {self.doc.loc(seen[k]).line}")
            seen.setdefault(k, p + ("command",))

    # -- telemetry: ROS 2 topic -> RAPID sample ------------------------------------------
    def feed(self, item: object, path: tuple) -> dict | None:
        if not self.mapping(item, path, _FEED_KEYS, ("topic", "type", "feeds")):
            return None
        assert isinstance(item, dict)
        topic = self.topic(item["topic"], path + ("topic",))
        msg = self.msg_type(item["type"], path + ("type",))
        kind = item["feeds"]
        if kind not in ("joint", "position", "agent", "image"):
            self.error("RG1505", f"'{kind}' is not a telemetry kind a ROS 2 topic can feed", path + ("feeds",),
                       "joint (from sensor_msgs/msg/JointState), position (PoseStamped, Pose, Odometry), agent "
                       "or image (Image, CompressedImage)")
            return None
        index = item.get("index", 0)
        if not isinstance(index, int) or isinstance(index, bool) or index < 0:
            self.error("RG1505", "index must be a number from 0", path + ("index",), "which entry of that kind")
            return None
        entries = [t for t in self.loaded.spec.telemetry if t.kind == kind]
        if index >= len(entries):
            self.error("RG1504", f"the descriptor declares {len(entries)} {kind} telemetry entr"
                       f"{'y' if len(entries) == 1 else 'ies'}, no entry {index}", path + ("feeds",),
                       f"add a 'kind: {kind}' entry under telemetry, or fix 'index'")
            return None
        if topic is None or msg is None:
            return None
        entry = entries[index]
        out: dict[str, Any] = {"topic": topic, "type": msg.name, "feeds": kind, "index": index,
                               "rate": entry.rate}
        for k, what in (("joints", "joint"), ("values", "agent")):
            if k in item and kind != what:
                self.error("RG1505", f"'{k}' is for {what} feeds", path + (k,), "leave it out")
        if kind == "joint":
            return self.joint_feed(item, path, msg, entry, out)
        if kind == "position":
            return self.position_feed(path, msg, entry, out)
        if kind == "image":
            return self.image_feed(path, msg, entry, out)
        return self.agent_feed(item, path, msg, entry, out)

    def joint_feed(self, item: dict, path: tuple, msg: msgdefs.MsgDef, entry: Any, out: dict) -> dict | None:
        if msg.name != JOINT_SOURCE:
            self.error("RG1503", f"{msg.name} cannot feed joint telemetry", path + ("type",),
                       f"joint telemetry comes from {JOINT_SOURCE} (names matched to the JointConfig's joints)")
            return None
        frames = [j.frame for j in entry.joints]
        names = item.get("joints", frames)
        if not isinstance(names, list) or not all(isinstance(n, str) and n for n in names):
            self.error("RG1505", "'joints' must be a list of ROS 2 joint names", path + ("joints",),
                       "one name per joint of the JointConfig, in its order")
            return None
        if len(names) != len(frames):
            self.error("RG1503", f"{len(names)} ROS 2 joint names for {len(frames)} RAPID joints",
                       path + ("joints",), "one name per joint of the JointConfig, in its order: "
                       + ", ".join(frames[:6]) + (", ..." if len(frames) > 6 else ""))
            return None
        out["joints"] = list(names)
        out["fields"] = list(entry.fields or ("anglePos",))
        return out

    def position_feed(self, path: tuple, msg: msgdefs.MsgDef, entry: Any, out: dict) -> dict | None:
        source = POSE_SOURCES.get(msg.name)
        if source is None:
            self.error("RG1503", f"{msg.name} cannot feed position telemetry", path + ("type",),
                       "position telemetry comes from " + ", ".join(sorted(POSE_SOURCES)))
            return None
        if entry.pose_encoding not in ENCODINGS:
            self.error("RG1503", f"the position entry's pose_encoding {entry.pose_encoding} cannot be made from a "
                       "ROS 2 quaternion", path + ("feeds",), "use " + ", ".join(ENCODINGS))
            return None
        if entry.velocity_encoding not in VELOCITY_ENCODINGS:
            self.error("RG1503", f"the position entry's velocity_encoding {entry.velocity_encoding} cannot be made "
                       "from a ROS 2 twist", path + ("feeds",), "use RAPID_ROT_NONE or RAPID_ROT_VEL")
            return None
        if entry.values:
            self.error("RG1503", "the position entry declares values a pose message does not carry",
                       path + ("feeds",), "move them to an agent entry fed by a topic")
            return None
        out.update(pose=source[0], twist=source[1], encoding=entry.pose_encoding,
                   velocity_encoding=entry.velocity_encoding)
        return out

    def image_feed(self, path: tuple, msg: msgdefs.MsgDef, entry: Any, out: dict) -> dict | None:
        mimes = IMAGE_SOURCES.get(msg.name)
        if mimes is None:
            self.error("RG1503", f"{msg.name} cannot feed image telemetry", path + ("type",),
                       "image telemetry comes from " + " or ".join(sorted(IMAGE_SOURCES)))
            return None
        if entry.mime not in mimes:
            self.error("RG1503", f"{msg.name} cannot carry the image entry's MIME type {entry.mime}",
                       path + ("type",), f"declare mime: {' or '.join(mimes)} on the entry"
                       + (" (a raw image is passed on as PNM)" if msg.name.endswith("/Image") else ""))
            return None
        return out

    def agent_feed(self, item: dict, path: tuple, msg: msgdefs.MsgDef, entry: Any, out: dict) -> dict | None:
        values = item.get("values")
        vpath = path + ("values",)
        if not isinstance(values, dict) or not values:
            self.error("RG1505", "an agent feed needs 'values': {value key: field path}", path,
                       "e.g. values: {batteryCharge: percentage}")
            return None
        keys = {v.name: v for v in entry.values}
        got = []
        for key, source in values.items():
            v = keys.get(key)
            if v is None:
                self.error("RG1504", f"the agent entry has no value '{key}'", vpath + (key,),
                           "its values: " + ", ".join(keys) if keys else "it declares no values", key=True)
                continue
            value = self.agent_value(msg, key, v, source, vpath + (key,))
            if value is not None:
                got.append(value)
        out["values"] = got
        return out

    def agent_value(self, msg: msgdefs.MsgDef, key: str, v: Any, source: object, where: tuple) -> list | None:
        """[key, field path, conversion, scale] for `path`, {field: path, scale: k} or {yaw: path}
        (a Quaternion's heading [rad], about z as tf2's getRPY)."""
        scale: float = 1
        conv_of = None
        if isinstance(source, dict):
            heads = [k for k in ("field", "yaw") if k in source]
            if len(heads) != 1 or not set(source) <= {"field", "yaw", "scale"}:
                self.error("RG1505", "a value is a field path, {field: PATH, scale: K} or {yaw: PATH, scale: K}",
                           where, "e.g. {field: percentage, scale: 100} (BatteryState's 0-1 as %)")
                return None
            scale = source.get("scale", 1)
            if isinstance(scale, bool) or not isinstance(scale, (int, float)) or not math.isfinite(scale) \
                    or scale == 0:
                self.error("RG1503", f"scale {scale!r} is not a finite number other than 0", where + ("scale",),
                           "the field's value is multiplied by it")
                return None
            if heads[0] == "yaw":
                conv_of = "yaw"
            where, source = where + (heads[0],), source[heads[0]]
        f = self.field(msg, source, where)
        if f is None:
            return None
        assert isinstance(source, str)
        conv: str | None
        if conv_of == "yaw":
            if f.type != QUAT or f.array or v.type not in ("RAPID_DOUBLE", "RAPID_FLOAT"):
                self.error("RG1503", f"yaw takes a geometry_msgs/Quaternion field into a RAPID_DOUBLE or RAPID_FLOAT; "
                           f"here {msg.name} '{source}' ({_spell(f)}) into {key} ({v.type})", where,
                           "e.g. heading: {yaw: pose.pose.orientation}")
                return None
            conv = "yaw"
        else:
            conv = _value_from(f, v.type)
            if conv is None:
                self.error("RG1503", f"{msg.name} field '{source}' ({_spell(f)}) cannot carry {key} ({v.type})",
                           where, _fits_hint(v.type))
                return None
            if scale != 1 and conv not in ("float", "vec3"):
                self.error("RG1503", f"{key} ({v.type}) cannot be scaled", where,
                           "scale goes with RAPID_DOUBLE, RAPID_FLOAT and RAPID_VEC3d values")
                return None
        if msg.name == BATTERY and source == "percentage" and scale == 1 and (v.unit or "").strip() in PERCENT:
            self.sink.warning("RG1509", f"{BATTERY} percentage is 0 to 1, and {key}'s unit is {v.unit}",
                              self.doc.loc(where), "write {field: percentage, scale: 100}, or declare the value "
                              "without a % unit (0-1)")
        return [key, source, conv, scale]

    # -- commands: RAPID command -> ROS 2 message ----------------------------------------
    def command(self, item: object, path: tuple) -> dict | None:
        if not self.mapping(item, path, _COMMAND_KEYS, ("command",)):
            return None
        assert isinstance(item, dict)
        name = self.text(item["command"], path + ("command",), "a command")
        if name is None:
            return None
        if sum(k in item for k in _DOINGS) != 1:
            self.error("RG1505", f"'{name}' needs exactly one of 'publish', 'call' and 'action'", path + ("command",),
                       "publish: {topic, type, fields}, call: {service, type, fields} or action: {action, type, fields}")
            return None
        if "until" in item and "publish" not in item:
            self.error("RG1505", "'until' is for 'publish' (a service call or an action goal ends with its result)",
                       path + ("until",), "leave it out")
            return None
        cmd = self.find_command(name, path + ("command",))
        if cmd is None:
            return None
        out: dict[str, Any] = {"command": name}
        parts = [("publish", self.publish), ("call", self.call), ("action", self.action), ("until", self.until_of),
                 ("cancel", self.publish)]
        for key, read in parts:
            if key in item:
                out[key] = read(item[key], path + (key,), cmd)
        if "cancel" in item and not cmd.abortable:
            self.error("RG1505", f"'{name}' is not abortable, so it is never cancelled", path + ("cancel",),
                       "set 'abortable: true' on the command, or leave 'cancel' out")
            return None
        return out if all(out[k] is not None for k, _ in parts if k in out) else None

    def until_of(self, value: object, path: tuple, cmd: Any) -> dict | None:
        return self.until(value, path)

    def action(self, value: object, path: tuple, cmd: Any) -> dict | None:
        """An action goal built from the arguments: feedback as EXECUTING acks, the result's
        status as COMPLETED (OK, EXEC_FAILED when aborted or rejected, CANCELED)."""
        head = self.typed(value, path, _ACTION_KEYS, "action", "action", msgdefs.full_action_name,
                          msgdefs.lookup_action, msgdefs.BUILTIN_ACTION)
        if head is None:
            return None
        name, full, found = head
        assert isinstance(value, dict)  # (typed() checked it)
        timeout = self.timeout(value, path)
        fields = self.fields_of(value.get("fields", {}), path, found[0], cmd)
        if fields is None or timeout is False:
            return None
        return {"action": name, "type": full, "fields": fields, "timeout": timeout}

    def typed(self, value: object, path: tuple, keys, key: str, kind: str, full_name, lookup,
              builtin) -> tuple[str, str, Any] | None:
        """The head of a service call or an action: its name (under `key`) and its installed
        or built-in ROS 2 type (`kind`: srv or action) -> (name, full type name, definitions)."""
        if not self.mapping(value, path, keys, (key, "type")):
            return None
        assert isinstance(value, dict)
        what = "a service type" if kind == "srv" else "an action type"
        name = self.topic(value[key], path + (key,))
        text = self.text(value["type"], path + ("type",), what)
        if name is None or text is None:
            return None
        full = full_name(text)
        found = lookup(full) if full else None
        if found is None:
            noun = "service" if kind == "srv" else "action"
            self.error("RG1501", f"unknown ROS 2 {noun} type {full or text}", path + ("type",),
                       f"write package/{kind}/Type; not installed (no share/<package>/{kind}/<Type>.{kind}) and not "
                       f"one of the built-in {', '.join(sorted(builtin))}")
            return None
        return name, full, found

    def timeout(self, value: dict, path: tuple) -> float | None | bool:
        """The timeout in seconds, None when not given, False (reported) when not above 0."""
        t = value.get("timeout")
        if t is not None and (isinstance(t, bool) or not isinstance(t, (int, float)) or t <= 0):
            self.error("RG1505", "timeout must be a number of seconds above 0", path + ("timeout",),
                       "leave it out to wait until the command is cancelled")
            return False
        return t

    def call(self, value: object, path: tuple, cmd: Any) -> dict | None:
        """A service call built from the arguments; its response's `success` (when it has one)
        decides COMPLETED/OK or EXEC_FAILED, its `message` becomes the ack's."""
        head = self.typed(value, path, _CALL_KEYS, "service", "srv", msgdefs.full_srv_name, msgdefs.lookup_srv,
                          msgdefs.BUILTIN_SRV)
        if head is None:
            return None
        service, name, (request, response) = head
        assert isinstance(value, dict)  # (typed() checked it)
        timeout = self.timeout(value, path)
        if timeout is False:
            return None
        fields = self.fields_of(value.get("fields", {}), path, request, cmd)
        if fields is None:
            return None
        success, message = response.field("success"), response.field("message")
        return {"service": service, "type": name, "fields": fields, "timeout": timeout,
                "success": success is not None and success.type == "bool" and not success.array,
                "message": message is not None and message.type == "string" and not message.array}

    def find_command(self, name: str, path: tuple) -> Any:
        sub, slash, cname = name.partition("/")
        subs = {s.name: s for s in self.loaded.subsystems}
        if not slash or sub not in subs:
            self.error("RG1504", f"'{name}' names no subsystem of the asset", path,
                       "write Subsystem/command; subsystems: " + ", ".join(subs))
            return None
        t = self.loaded.types.get(subs[sub].type)
        cmd = next((c for c in (t.commands if t else ()) if c.name == cname), None)
        if cmd is None:
            self.error("RG1504", f"subsystem '{sub}' has no command '{cname}'", path,
                       "its commands: " + ", ".join(c.name for c in (t.commands if t else ())))
        return cmd

    def publish(self, value: object, path: tuple, cmd: Any) -> dict | None:
        if not self.mapping(value, path, _PUBLISH_KEYS, ("topic", "type")):
            return None
        assert isinstance(value, dict)
        topic = self.topic(value["topic"], path + ("topic",))
        msg = self.msg_type(value["type"], path + ("type",))
        if topic is None or msg is None:
            return None
        got = self.fields_of(value.get("fields", {}), path, msg, cmd)
        if got is None:
            return None
        header = msg.field("header")  # stamped with the time of sending
        return {"topic": topic, "type": msg.name, "fields": got,
                "stamp": header is not None and header.type == "std_msgs/msg/Header"}

    def fields_of(self, fields: object, path: tuple, msg: msgdefs.MsgDef, cmd: Any) -> list | None:
        """[field path, conversion, parameter indices or constant] per field to fill."""
        if not isinstance(fields, dict):
            self.error("RG1505", "'fields' must map field paths to parameters", path + ("fields",),
                       "e.g. fields: {pose.position: xyz}")
            return None
        params = {p.name: (i, p) for i, p in enumerate(cmd.parameters)}
        got = []
        good = True
        for fpath, source in fields.items():
            where = path + ("fields", fpath)
            f = self.field(msg, fpath, where, key=True)
            conv = self.source(f, fpath, source, where, params, msg.name) if f is not None else None
            if conv is None:
                good = False
                continue
            got.append([fpath, *conv])
        return got if good else None

    def source(self, f: Field, fpath: str, source: object, where: tuple, params: dict, mname: str) -> list | None:
        """[conversion, references or a constant]: how the field is filled. A reference is a
        parameter's index (the whole argument) or [index, element or None, scale]."""
        if isinstance(source, dict) and "value" in source:
            if set(source) != {"value"}:
                self.error("RG1505", "a constant is written {value: ...}, alone", where, "or name a parameter")
                return None
            const = source["value"]
            if _const_fits(f, const):
                return ["const", const]
            self.error("RG1503", f"{const!r} does not fit {mname} field '{fpath}' ({_spell(f)})", where,
                       "give a value of the field's type")
            return None
        if isinstance(source, dict) and (set(source) & set(EULER) or (f.type == QUAT and "from" not in source)):
            return self.euler(f, fpath, source, where, params, mname)
        listed = isinstance(source, list)
        items: list = source if isinstance(source, list) else [source]
        found = [self.reference(s, where, params) for s in items]
        got = [g for g in found if g is not None]
        if len(got) != len(found) or not got:
            if not found:
                self.error("RG1505", "an empty list fills nothing", where, "name the parameters to put in the field")
            return None
        refs, types = [g[0] for g in got], [g[1] for g in got]
        conv = _arg_to_field(f, types, listed)
        if conv is None:
            self.error("RG1503", f"{', '.join(g[2] for g in got)} does not fit {mname} field '{fpath}' ({_spell(f)})",
                       where, _field_hint(f))
            return None
        if conv == "quat_rpy":  # a vector of angles only: simpleMove's xyt (m, m, rad) is no roll, pitch, yaw
            index = refs[0] if isinstance(refs[0], int) else refs[0][0]
            param = next(q for i, q in params.values() if i == index)
            units = [u.strip() for u in (param.unit or "").split(",") if u.strip()]
            if units and not all(u in ANGLE_UNITS for u in units):
                self.error("RG1503", f"{param.name} ({param.unit}) is not roll, pitch, yaw: a quaternion from it would "
                           "turn its lengths into angles", where,
                           f"pick its angle: pose.orientation: {{yaw: \"{param.name}[{len(units) - 1}]\"}}"
                           if len(units) == 3 and units[-1] in ANGLE_UNITS else "map its angles with {roll, pitch, yaw}")
                return None
        scaled = [r for r in refs if isinstance(r, list) and r[2] != 1]
        if scaled and conv not in SCALABLE:
            self.error("RG1503", f"a {_spell(f)} field cannot be scaled", where,
                       "scale goes with float fields, float arrays, Point/Vector3 and roll-pitch-yaw quaternions")
            return None
        return [conv, refs]

    def reference(self, source: object, where: tuple, params: dict) -> tuple[Any, str, str] | None:
        """(reference, the RAPID type it gives, how to name it) for `name`, `name[i]` (one element
        of a RAPID_VEC3d or RAPID_MAT33f) or {from: name or name[i], scale: k}."""
        scale: float = 1
        if isinstance(source, dict):
            if "from" not in source or not set(source) <= {"from", "scale"}:
                self.error("RG1505", "a scaled argument is written {from: PARAMETER, scale: NUMBER}", where,
                           "e.g. {from: 'xyt[2]', scale: 57.29578}; a constant is {value: ...}")
                return None
            scale = source.get("scale", 1)
            if isinstance(scale, bool) or not isinstance(scale, (int, float)) or not math.isfinite(scale) \
                    or scale == 0:
                self.error("RG1503", f"scale {scale!r} is not a finite number other than 0", where + ("scale",),
                           "the argument is multiplied by it (e.g. 0.001 for mm to m)")
                return None
            source = source["from"]
        if not isinstance(source, str) or not source:
            self.error("RG1505", f"{source!r} names no parameter", where,
                       "write a parameter name, name[i] for one element, {from: ..., scale: ...} or {value: ...}")
            return None
        name, element = source, None
        m = _ELEMENT.match(source)
        if source not in params and m is not None:
            name, element = m.group(1), int(m.group(2))
        if name not in params:
            self.error("RG1504", f"the command has no parameter {name!r}", where,
                       "its parameters: " + (", ".join(params) or "none") + "; a constant is {value: ...}")
            return None
        index, param = params[name]
        ptype = param.type
        if element is not None:
            size = ELEMENTS.get(ptype)
            if size is None:
                self.error("RG1503", f"{name} ({ptype}) has no elements to pick", where,
                           "name[i] picks from a RAPID_VEC3d (0-2) or a RAPID_MAT33f (0-8, row-major)")
                return None
            if element >= size:
                self.error("RG1503", f"{source}: a {ptype} has elements 0 to {size - 1}", where,
                           "RAPID_VEC3d xyt: x 0, y 1, heading 2" if ptype == "RAPID_VEC3d" else "row-major 3x3")
                return None
            ptype = "RAPID_DOUBLE"
        if scale != 1 and ptype not in NUMERIC + ("RAPID_VEC3d", "RAPID_MAT33f"):
            self.error("RG1503", f"{source} ({ptype}) cannot be scaled", where, "scale numbers and vectors")
            return None
        ref: Any = index if element is None and scale == 1 else [index, element, scale]
        return ref, ptype, f"{source} ({ptype})"

    def euler(self, f: Field, fpath: str, source: dict, where: tuple, params: dict, mname: str) -> list | None:
        """{roll, pitch, yaw} -> a Quaternion: each angle [rad] one numeric argument (an element,
        a number parameter, scaled or not), an angle left out 0; as tf2's setRPY."""
        if f.type != QUAT or f.array:
            self.error("RG1503", f"roll/pitch/yaw make a quaternion; {mname} field '{fpath}' is {_spell(f)}", where,
                       "map them onto a geometry_msgs/Quaternion field (e.g. pose.orientation)")
            return None
        extra = [k for k in source if k not in EULER]
        if extra:
            self.error("RG1505", f"unknown key '{extra[0]}' in a roll/pitch/yaw orientation", where + (extra[0],),
                       "keys here: roll, pitch, yaw (each a number argument; left out: 0)", key=True)
            return None
        angles: list[Any] = []
        for k in EULER:
            if k not in source:
                angles.append(None)
                continue
            got = self.reference(source[k], where + (k,), params)
            if got is None:
                return None
            if got[1] not in NUMERIC:
                self.error("RG1503", f"{got[2]} is not one angle", where + (k,),
                           f"{k} takes a number: pick an element (e.g. xyt[2], the heading of simpleMove's xyt) "
                           "or a number parameter")
                return None
            angles.append(got[0])
        return ["quat_euler", angles]

    def until(self, value: object, path: tuple) -> dict | None:
        if not self.mapping(value, path, _UNTIL_KEYS, ("topic", "type", "field", "equals")):
            return None
        assert isinstance(value, dict)
        topic = self.topic(value["topic"], path + ("topic",))
        msg = self.msg_type(value["type"], path + ("type",))
        timeout = value.get("timeout")
        if timeout is not None and (isinstance(timeout, bool) or not isinstance(timeout, (int, float))
                                    or timeout <= 0):
            self.error("RG1505", "timeout must be a number of seconds above 0", path + ("timeout",),
                       "leave it out to wait until the command is cancelled")
            return None
        if topic is None or msg is None:
            return None
        f = self.field(msg, value["field"], path + ("field",))
        if f is None:
            return None
        if not _const_fits(f, value["equals"]):
            self.error("RG1503", f"{value['equals']!r} does not fit {msg.name} field '{value['field']}' "
                       f"({_spell(f)})", path + ("equals",), "give a value of the field's type")
            return None
        return {"topic": topic, "type": msg.name, "field": value["field"], "equals": value["equals"],
                "timeout": timeout}


# -- what fits what ------------------------------------------------------------------------
def _spell(f: Field) -> str:
    return f.type + ("[]" if f.array and f.size is None else f"[{f.size}]" if f.array else "")


def _value_from(f: Field, dtype: str) -> str | None:
    """How a message field becomes an AgentState value of dtype, or None."""
    if f.array:
        return None
    if dtype in NUMERIC and (f.type in FLOATS or f.type in INTEGERS):
        return "int" if dtype in ("RAPID_INT", "RAPID_LONGLONG") and f.type in INTEGERS else \
            "float" if dtype in ("RAPID_DOUBLE", "RAPID_FLOAT") else None
    if dtype == "RAPID_BOOL" and f.type == "bool":
        return "bool"
    if dtype == "RAPID_STRING" and f.type == "string":
        return "str"
    if dtype == "RAPID_VEC3d" and f.type in VEC3_MSGS:
        return "vec3"
    return None


def _fits_hint(dtype: str) -> str:
    return {"RAPID_VEC3d": "a geometry_msgs Point or Vector3 field", "RAPID_BOOL": "a bool field",
            "RAPID_STRING": "a string field", "RAPID_INT": "an integer field",
            "RAPID_LONGLONG": "an integer field"}.get(dtype, "a float32/float64 field (or an integer)")


def _arg_to_field(f: Field, types: list[str], listed: bool) -> str | None:
    """How command arguments of `types` fill field f, or None when they do not fit."""
    numeric = all(t in NUMERIC for t in types)
    if f.array:
        if f.type in FLOATS and listed and numeric and (f.size is None or f.size == len(types)):
            return "list"
        if f.type in FLOATS and not listed and types[0] in ("RAPID_VEC3d", "RAPID_MAT33f") and \
                (f.size is None or f.size == (3 if types[0] == "RAPID_VEC3d" else 9)):
            return "list"
        return None
    if listed and len(types) != 1:
        return None
    t = types[0]
    if f.type in FLOATS:
        return "float" if t in NUMERIC else None
    if f.type in INTEGERS:
        return "int" if t in ("RAPID_INT", "RAPID_LONGLONG") else None
    if f.type == "bool":
        return "bool" if t == "RAPID_BOOL" else None
    if f.type == "string":
        return "str" if t == "RAPID_STRING" else None
    if f.type in VEC3_MSGS:
        return "vec3" if t == "RAPID_VEC3d" else None
    if f.type == QUAT:
        return {"RAPID_VEC3d": "quat_rpy", "RAPID_MAT33f": "quat_m33"}.get(t)
    return None


def _field_hint(f: Field) -> str:
    if f.array:
        return "a float array takes a list of numeric parameters, a RAPID_VEC3d or a RAPID_MAT33f"
    if f.type == QUAT:
        return "a quaternion takes a RAPID_VEC3d (roll, pitch, yaw) or a RAPID_MAT33f (rotation matrix)"
    if f.type in VEC3_MSGS:
        return "a Point or Vector3 takes a RAPID_VEC3d"
    if f.type in INTEGERS:
        return "an integer field takes RAPID_INT or RAPID_LONGLONG"
    if f.type in FLOATS:
        return "a float field takes RAPID_FLOAT, RAPID_DOUBLE, RAPID_INT or RAPID_LONGLONG"
    if f.primitive:
        return f"a {f.type} field takes a RAPID_{'BOOL' if f.type == 'bool' else 'STRING'}"
    return "map its primitive fields one by one (e.g. pose.position.x)"


def _const_fits(f: Field, value: object) -> bool:
    if f.array:
        return False
    if f.type == "bool":
        return isinstance(value, bool)
    if f.type == "string":
        return isinstance(value, str)
    if f.type in INTEGERS:
        return isinstance(value, int) and not isinstance(value, bool)
    if f.type in FLOATS:
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    return False


def _levels(t: Any) -> list | None:
    """A threshold as [below, above] (None for an open side), or None without one."""
    return None if t is None else [t.below, t.above]


def read_ros2(doc: YamlDoc, loaded: Any, sink: DiagnosticSink) -> dict | None:
    """The checked mapping as plain data (see ros2_map.py in the generated package), or None
    with errors in the sink. `loaded` is the descriptor's LoadedAsset."""
    assert isinstance(doc.data, dict)
    return _Reader(doc, loaded, sink).read(doc.data["ros2"])
