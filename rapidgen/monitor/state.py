"""What the page shows, as plain data: every asset (partition) with its status, command
dictionary, values (coloured by the descriptor's thresholds), plots, position and traverse,
latest pictures, text log, queue, access control and acks. Fed with decoded samples by the
live watcher or by a recording; no DDS and no HTTP here.

Clients get deltas: every change takes the next number of one counter (`Hub.seq`); a client
remembers the last number it saw and gets the sections changed since, plus the stream items
(plot points, traverse points, log lines) added since. Everything kept is bounded.
"""
from __future__ import annotations

import collections
import math
import threading
import time
from dataclasses import dataclass, field

from rapidgen.monitor.hints import Hints, level_of
from rapidgen.spy.model import plain

TEXT = 512  # characters kept of one string from the network (the log: LOG_TEXT)
LOG_TEXT = 2048
LOG_LINES = 200
ACKED_COMMANDS = 32  # commands whose ack sequence is kept, per asset
ACKS_PER_COMMAND = 16
POINTS = 20_000  # plot points kept per asset (each series also thinned to PLOT_STEP)
PLOT_STEP = 0.25  # seconds between two points of one series
TRAVERSE = 5_000  # positions kept per asset
TRAVERSE_STEP = 0.02  # metres moved before a new traverse point
CUSTOM_FIELDS = 32  # scalar fields of an extension sample shown
MAX_ASSETS = 64  # assets shown besides the --asset ones (which always get a place)
MAX_NAMED_DROPPED = 1024  # partitions not shown, remembered by name up to this many, then counted
MAX_ROWS = 256  # value rows kept per asset, whatever its configs declare
CONFIG_WRITERS = 16  # writers of one config topic remembered per asset
MAX_IMAGES = 16  # sensors per asset
STALE = 5.0  # seconds without a sample: the asset is shown as quiet


def _text(v: object, n: int = TEXT) -> str:
    return v[:n] if isinstance(v, str) else ""


def _num(v: object) -> float | None:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    return float(v)


def _json_num(v: float) -> float | str:
    return v if math.isfinite(v) else ("NaN" if v != v else ("Infinity" if v > 0 else "-Infinity"))


def _union(u) -> tuple[str, object]:
    """(DataType name, plain value) of a ParameterUnion."""
    d = getattr(u, "discriminator", None)
    v = getattr(u, "value", None)
    return getattr(d, "name", str(d)), plain(list(v) if isinstance(v, (list, tuple)) else v)


def short(type_name: str) -> str:
    return type_name.replace(".", "::").rsplit("::", 1)[-1]


@dataclass
class Asset:
    partition: str
    name: str = ""
    last: float = 0.0  # wall time of the newest sample
    status_code: int | None = None
    present: bool | None = None  # a writer of it is on the network (None: not known, a replay)
    sections: dict[str, tuple[int, object]] = field(default_factory=dict)  # name -> (seq, data)
    values: dict[str, dict] = field(default_factory=dict)  # value id -> row
    value_keys: dict[str, list[tuple[str, str]]] = field(default_factory=dict)  # topic -> [(key, type)]
    joint_frames: list[str] = field(default_factory=list)
    pose_encoding: str = "RAPID_ROT_QUAT"
    points: collections.deque = field(default_factory=lambda: collections.deque(maxlen=POINTS))
    last_point: dict[str, float] = field(default_factory=dict)
    traverse: collections.deque = field(default_factory=lambda: collections.deque(maxlen=TRAVERSE))
    log: collections.deque = field(default_factory=lambda: collections.deque(maxlen=LOG_LINES))
    acks: collections.OrderedDict = field(default_factory=collections.OrderedDict)  # cmdId -> dict
    images: dict[str, dict] = field(default_factory=dict)  # sensor -> meta (bytes in Hub.pictures)
    # rows: each group (agent, position, joint, an extension topic) keeps as many as its
    # configs declare (else as many as one sample carries), the least recently updated go
    group_rows: dict[str, dict[str, int]] = field(default_factory=dict)  # group -> topic -> declared rows
    rows_dropped: int = 0
    config_writers: dict[str, dict[str, float]] = field(default_factory=dict)  # config topic -> writer -> time
    command_configs: dict[str, tuple[dict, str | None]] = field(default_factory=dict)  # writer -> (config, diff)
    discovered: set[str] = field(default_factory=set)  # config writers discovery has listed


class Hub:
    """Every asset's state, shared by the feeding thread and the web server (one lock)."""

    def __init__(self, hints: Hints | None = None, clock=time.time) -> None:
        self.hints = hints or Hints()
        self.clock = clock
        self.lock = threading.RLock()
        self.seq = 0
        self.assets: dict[str, Asset] = {}
        self.pictures: dict[tuple[str, str], tuple[str, bytes, int]] = {}  # (partition, sensor) -> mime, data, seq
        self.dropped_assets = 0  # partitions not shown (MAX_ASSETS)
        self.dropped_names: set[str] = set()
        self.notes: list[str] = []  # what the feeder says (undecodable samples, caps)
        self._writer: str | None = None  # the writer of the sample being handled

    def _next(self) -> int:
        self.seq += 1
        return self.seq

    def _set(self, a: Asset, section: str, data: object) -> None:
        a.sections[section] = (self._next(), data)

    def asset(self, partition: str) -> Asset | None:
        a = self.assets.get(partition)
        if a is None:
            if not self.hints.declared(partition) and \
                    sum(1 for p in self.assets if not self.hints.declared(p)) >= MAX_ASSETS:
                if partition not in self.dropped_names:
                    self.dropped_assets += 1
                    if len(self.dropped_names) < MAX_NAMED_DROPPED:
                        self.dropped_names.add(partition)
                return None
            a = self.assets[partition] = Asset(partition)
            self._set(a, "commands", self.hints.commands_for(partition, None))
        return a

    # ---- feeding -----------------------------------------------------------------------------
    def sample(self, partition: str, topic: str, type_name: str, s, t: float | None = None,
               writer: str | None = None) -> None:
        """One decoded sample of `topic` in `partition` (t: its wall time, default now;
        writer: its writer's GUID, when known)."""
        t = self.clock() if t is None else t
        kind = short(type_name)
        with self.lock:
            a = self.asset(partition)
            if a is None:
                return
            hdr = getattr(s, "hdr", None)
            name = _text(getattr(hdr, "assetName", ""), 64)
            if name and kind not in ("Command", "Ack") and name != a.name:
                a.name = name
            a.last = max(a.last, t)
            if writer is not None and kind.endswith("Config"):
                self._config_writer(a, topic, writer, t)
            self._writer = writer
            handler = getattr(self, "_on_" + kind, None)
            if handler is not None:
                handler(a, topic, s, t)
            elif kind.endswith(("Sample", "State")):
                self._custom(a, topic, s, t)
            self._status(a)

    def _status(self, a: Asset) -> None:
        data = {"name": a.name or a.partition, "partition": a.partition, "last": a.last,
                "statusCode": a.status_code, "present": a.present}
        if a.sections.get("status", (0, None))[1] != data:
            self._set(a, "status", data)

    def _config_writer(self, a: Asset, topic: str, writer: str, t: float) -> None:
        writers = a.config_writers.setdefault(topic, {})
        if writer not in writers and len(writers) >= CONFIG_WRITERS:
            return
        new = writer not in writers
        writers[writer] = t
        if new:
            self._alerts(a)

    def _on_CommandConfig(self, a: Asset, topic: str, s, t: float) -> None:
        from rapid_runtime.messages import config_plain
        config = config_plain(s)
        writer = self._writer or ""
        if writer in a.command_configs or len(a.command_configs) < CONFIG_WRITERS:
            a.command_configs[writer] = (config, self.hints.config_differs(a.partition, config))
        self._commands(a, config)

    def _commands(self, a: Asset, config: dict | None) -> None:
        """The commands section: `config` as the page's dictionary, refused while any writer's
        CommandConfig differs from the --asset descriptor's."""
        out = self.hints.commands_for(a.partition, config)
        bad = [(w, d) for w, (_c, d) in a.command_configs.items() if d]
        if bad:
            w, d = bad[0]
            out["refused"] = (f"the live CommandConfig {'of writer ' + w[:40] + ' ' if w else ''}differs from the "
                              f"--asset descriptor's: {d}. Commands to this asset are refused until that writer "
                              "leaves (a rogue publisher, or the wrong descriptor)")
        self._set(a, "commands", out)
        self._alerts(a)

    def _alerts(self, a: Asset) -> None:
        """What the operator must know about an asset before trusting its page."""
        out = []
        commands = a.sections.get("commands", (0, {}))[1]
        if isinstance(commands, dict) and commands.get("refused"):
            out.append(commands["refused"])
        for topic, writers in sorted(a.config_writers.items()):
            if len(writers) > 1:
                out.append(f"{len(writers)}{'+' if len(writers) >= CONFIG_WRITERS else ''} writers publish "
                           f"{_text(topic, 128)} in this partition: " + ", ".join(sorted(writers)[:4]))
        if a.sections.get("alerts", (0, []))[1] != out:
            self._set(a, "alerts", out)

    def _keys(self, a: Asset, topic: str, s) -> None:
        a.value_keys[topic] = [(_text(k.key, 64), _union(k.value)[0]) for k in s.valueKeys]

    def _on_AgentConfig(self, a: Asset, topic: str, s, t: float) -> None:
        self._keys(a, "rapid_agent_state" + topic[len("rapid_agent_config"):], s)

    def _on_PositionConfig(self, a: Asset, topic: str, s, t: float) -> None:
        self._keys(a, "rapid_position_sample" + topic[len("rapid_position_config"):], s)
        a.pose_encoding = getattr(s.poseEncoding, "name", str(s.poseEncoding))

    def _on_JointConfig(self, a: Asset, topic: str, s, t: float) -> None:
        a.joint_frames = [_text(j.frameName, 64) for j in s.jointDefinitions]

    def _declare_rows(self, a: Asset, group: str, topic: str, n: int) -> None:
        topics = a.group_rows.setdefault(group, {})
        if topic in topics or len(topics) < 64:
            topics[topic] = n

    def _values(self, a: Asset, group: str, topic: str, values, t: float) -> None:
        keys = a.value_keys.get(topic, [])
        values = list(values)
        self._declare_rows(a, group, topic, max(len(keys), len(values)))  # (keys: the config's declared count)
        for i, u in enumerate(values):
            dtype, v = _union(u)
            key = keys[i][0] if i < len(keys) else f"values[{i}]"
            self._value(a, group, key, dtype, v, t)

    def _value(self, a: Asset, group: str, key: str, dtype: str, v: object, t: float) -> None:
        hint = self.hints.value(a.partition, key)
        n = _num(v)
        row = {"group": group, "key": key, "type": dtype, "unit": hint.get("unit") if hint else None,
               "value": _json_num(n) if n is not None else (_text(v) if isinstance(v, str) else v),
               "level": level_of(n, hint) if n is not None else "ok", "t": t,
               "warning": hint.get("warning") if hint else None, "critical": hint.get("critical") if hint else None}
        vid = f"{group}/{key}"
        if vid not in a.values:
            self._room(a, group)
        a.values[vid] = row
        self._set(a, "values", list(a.values.values()))
        if n is not None and math.isfinite(n) and t - a.last_point.get(vid, -1e18) >= PLOT_STEP:
            a.last_point[vid] = t
            a.points.append((self._next(), vid, t, n))

    def _on_AgentState(self, a: Asset, topic: str, s, t: float) -> None:
        a.status_code = getattr(s.hdr, "statusCode", None)
        self._values(a, "agent", topic, s.values, t)

    def _on_PositionSample(self, a: Asset, topic: str, s, t: float) -> None:
        xyz = [float(x) for x in s.pose.xyz]
        rot = [float(x) for x in s.pose.rot]
        heading = _heading(rot, a.pose_encoding)
        self._set(a, "position", {"xyz": [_json_num(x) for x in xyz], "heading": _json_num(heading), "t": t})
        if all(math.isfinite(x) for x in xyz[:2]):
            last = a.traverse[-1] if a.traverse else None
            if last is None or math.hypot(xyz[0] - last[1], xyz[1] - last[2]) >= TRAVERSE_STEP:
                a.traverse.append((self._next(), xyz[0], xyz[1], t))
        self._values(a, "position", topic, s.values, t)

    def _room(self, a: Asset, group: str) -> None:
        """Room for a new row of `group`: past the group's declared count (or MAX_ROWS for
        the asset), the least recently updated row goes (counted)."""
        cap = max(1, min(MAX_ROWS, sum(a.group_rows.get(group, {}).values()) or CUSTOM_FIELDS))
        mine = [(r["t"], vid) for vid, r in a.values.items() if r["group"] == group]
        drop = sorted(mine)[:max(0, len(mine) - cap + 1)]
        if len(a.values) - len(drop) >= MAX_ROWS:
            rest = sorted((r["t"], vid) for vid, r in a.values.items() if r["group"] != group)
            drop += rest[:len(a.values) - len(drop) - MAX_ROWS + 1]
        for _t, vid in drop:
            del a.values[vid]
            a.last_point.pop(vid, None)
        if drop:
            a.rows_dropped += len(drop)
            self._set(a, "dropped", {"rows": a.rows_dropped, "cap": MAX_ROWS})

    def _on_JointSample(self, a: Asset, topic: str, s, t: float) -> None:
        self._declare_rows(a, "joint", topic, min(64, len(a.joint_frames) or len(s.anglePos)))
        for i, v in enumerate(list(s.anglePos)[:64]):
            frame = a.joint_frames[i] if i < len(a.joint_frames) else f"joint[{i}]"
            self._value(a, "joint", frame, "RAPID_FLOAT", float(v), t)

    def _on_TextMessage(self, a: Asset, topic: str, s, t: float) -> None:
        level = getattr(s.level, "name", str(s.level)).removeprefix("MSG_")
        a.log.append((self._next(), t, level, _text(s.category, 64), _text(s.message, LOG_TEXT)))

    def _on_QueueState(self, a: Asset, topic: str, s, t: float) -> None:
        def recs(q):
            return [{"cmdId": _text(r.cmd.cmdId, 64), "command": f"{_text(r.cmd.subsysName, 64)}/{_text(r.cmd.cmdName, 64)}",
                     "status": getattr(r.trStatus, "name", str(r.trStatus)).removeprefix("Q_STATUS_")}
                    for r in list(q.records)[:64]]
        state = {-1: "suspended", 0: "idle", 1: "active"}.get(s.hdr.statusCode, str(s.hdr.statusCode))
        self._set(a, "queue", {"state": state, "pending": recs(s.pending), "active": recs(s.active),
                               "completed": recs(s.completed)})

    def _on_AccessControlState(self, a: Asset, topic: str, s, t: float) -> None:
        self._set(a, "access", {"controller": _text(s.controller, 64),
                                "requestors": [_text(r, 64) for r in list(s.requestors)[:16]]})

    def _on_ImageSensorState(self, a: Asset, topic: str, s, t: float) -> None:
        sensor = _text(s.meta.sensorName, 64)
        if sensor not in a.images and len(a.images) < MAX_IMAGES:
            a.images[sensor] = {"sensor": sensor, "type": _text(s.meta.sensorType, 64), "width": s.meta.width,
                                "height": s.meta.height, "mime": None, "seq": 0, "t": None}
            self._set(a, "images", sorted(a.images.values(), key=lambda i: i["sensor"]))

    def _on_ImageSensorSample(self, a: Asset, topic: str, s, t: float) -> None:
        sensor = _text(s.meta.sensorName, 64)
        if sensor not in a.images and len(a.images) >= MAX_IMAGES:
            return
        seq = self._next()
        mime = _text(s.mimeType, 64)
        self.pictures[(a.partition, sensor)] = (mime, bytes(s.data), seq)
        a.images[sensor] = {"sensor": sensor, "type": _text(s.meta.sensorType, 64), "width": s.meta.width,
                            "height": s.meta.height, "mime": mime, "seq": seq, "t": t, "bytes": len(s.data)}
        self._set(a, "images", sorted(a.images.values(), key=lambda i: i["sensor"]))

    def _on_Ack(self, a: Asset, topic: str, s, t: float) -> None:
        cmd_id = _text(s.cmdId, 128)
        entry = a.acks.get(cmd_id)
        if entry is None:
            entry = a.acks[cmd_id] = {"cmdId": cmd_id, "command": "", "source": _text(s.hdr.srcName, 64), "acks": []}
            while len(a.acks) > ACKED_COMMANDS:
                a.acks.popitem(last=False)
        if len(entry["acks"]) < ACKS_PER_COMMAND:
            entry["acks"].append({"status": getattr(s.status, "name", str(s.status)).removeprefix("ACK_"),
                                  "completed": getattr(s.completedStatus, "name", str(s.completedStatus))
                                  .removeprefix("ACK_COMPLETED_"), "message": _text(s.message, 128), "t": t})
        self._set(a, "acks", list(a.acks.values())[::-1])

    def _on_Command(self, a: Asset, topic: str, s, t: float) -> None:
        self.command_seen(a.partition, _text(s.cmdId, 128), f"{_text(s.subsysName, 64)}/{_text(s.cmdName, 64)}",
                          _text(s.cmdSrc, 64))

    def command_seen(self, partition: str, cmd_id: str, label: str, source: str) -> None:
        """A command sent (by us or another commander): its ack sequence gets a name."""
        with self.lock:
            a = self.asset(partition)
            if a is None:
                return
            entry = a.acks.get(cmd_id)
            if entry is None:
                entry = a.acks[cmd_id] = {"cmdId": cmd_id, "command": label, "source": source, "acks": []}
                while len(a.acks) > ACKED_COMMANDS:
                    a.acks.popitem(last=False)
            else:
                entry.update(command=label, source=source)
            self._set(a, "acks", list(a.acks.values())[::-1])

    def _custom(self, a: Asset, topic: str, s, t: float) -> None:
        """An extension type's sample or state: its scalar fields as values."""
        flat: list[tuple[str, object]] = []
        _flatten(plain(s), "", flat)
        self._declare_rows(a, topic, topic, len(flat))
        for key, v in flat[:CUSTOM_FIELDS]:
            self._value(a, topic, key, "", v, t)

    def presence(self, partitions: set[str], writers: set[str] | None = None) -> None:
        """The partitions that have a writer now (from discovery): the others are gone; and
        (writers: their GUIDs) config writers that left are forgotten."""
        with self.lock:
            for p, a in self.assets.items():
                if a.present != (p in partitions):
                    a.present = p in partitions
                    self._status(a)
                if writers is None:
                    continue
                # a writer is forgotten once discovery listed it and no longer does (one its
                # full tables never listed stays: a flood of endpoints must not clear a warning)
                mine = set(a.command_configs) | {w for ws in a.config_writers.values() for w in ws}
                a.discovered |= mine & writers
                left = a.discovered - writers
                a.discovered -= left
                gone = [w for w in a.command_configs if w in left]
                for w in gone:
                    del a.command_configs[w]
                for ws in a.config_writers.values():
                    for w in [w for w in ws if w in left]:
                        del ws[w]
                if gone:  # the dictionary shown: another writer's config, else the descriptor's
                    others = list(a.command_configs.values())
                    self._commands(a, others[-1][0] if others else None)
                self._alerts(a)

    def all_notes(self) -> list[str]:
        """The feeder's notes and what the hub itself left out."""
        out = list(self.notes)
        with self.lock:
            if self.dropped_assets:
                names = ", ".join(repr(p[:40]) for p in sorted(self.dropped_names)[:3])
                out.append(f"{self.dropped_assets} partition(s) not shown (cap {MAX_ASSETS} besides the --asset ones, "
                           f"which always get a place), e.g. {names}")
            rows = sum(a.rows_dropped for a in self.assets.values())
            if rows:
                out.append(f"{rows} value row(s) dropped (rows per asset: as many as its configs declare, at most "
                           f"{MAX_ROWS}; the least recently updated go)")
        return out

    # ---- reading (the server) ------------------------------------------------------------------
    def delta(self, cursor: int, now: float | None = None) -> tuple[int, list[dict]]:
        """(the newest number, one message per asset with what changed after `cursor`)."""
        now = self.clock() if now is None else now
        out = []
        with self.lock:
            for a in self.assets.values():
                msg: dict = {"partition": a.partition}
                for name, (seq, data) in a.sections.items():
                    if seq > cursor:
                        msg[name] = data
                pts = [p[1:] for p in _after(a.points, cursor) if p[1] in a.values]  # rows dropped: their points too
                if pts:
                    msg["points"] = pts
                trav = [p[1:] for p in _after(a.traverse, cursor)]
                if trav:
                    msg["traverse"] = trav
                log = [p[1:] for p in _after(a.log, cursor)]
                if log:
                    msg["log"] = log
                if len(msg) > 1:
                    out.append(msg)
            return self.seq, out

    def stale(self, now: float | None = None) -> dict[str, bool]:
        now = self.clock() if now is None else now
        with self.lock:
            return {p: now - a.last > STALE for p, a in self.assets.items()}

    def picture(self, partition: str, sensor: str) -> tuple[str, bytes] | None:
        with self.lock:
            got = self.pictures.get((partition, sensor))
            return None if got is None else (got[0], got[1])


def _after(items: collections.deque, cursor: int) -> list:
    """Items (seq first) with seq > cursor: the deque is in seq order, read from the end."""
    out = []
    for item in reversed(items):
        if item[0] <= cursor:
            break
        out.append(item)
    return out[::-1]


def _flatten(v: object, prefix: str, out: list, depth: int = 0) -> None:
    if len(out) >= CUSTOM_FIELDS or depth > 4:
        return
    if isinstance(v, dict):
        for k, x in v.items():
            if not prefix and k == "hdr":
                continue
            _flatten(x, f"{prefix}.{k}" if prefix else str(k), out, depth + 1)
    elif isinstance(v, list):
        if len(v) <= 9 and all(isinstance(x, (int, float, str)) for x in v):
            for i, x in enumerate(v):
                _flatten(x, f"{prefix}[{i}]", out, depth + 1)
    elif isinstance(v, (int, float, str, bool)):
        out.append((prefix, v))


def _heading(rot: list[float], encoding: str) -> float:
    """Yaw [rad] of Transform3D.rot as PositionConfig.poseEncoding says: a quaternion
    (x, y, z, w), Euler angles (X-Y-Z, Z-Y-X) or a row-major 3x3 matrix; 0 for anything else."""
    if len(rot) < 9:
        return 0.0
    if encoding == "RAPID_ROT_QUAT":
        x, y, z, w = rot[:4]
        return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    if encoding == "RAPID_ROT_XYZ":
        return rot[2]
    if encoding == "RAPID_ROT_ZYX":
        return rot[0]
    if encoding == "RAPID_ROT_M33":
        return math.atan2(rot[3], rot[0])
    return 0.0
