"""`rapidgen record --foxglove`: beside each RAPID channel, the derived channels of
rapidgen.foxglove (docs/foxglove.md), `json` messages whose schemas are Foxglove's published
JSON Schemas (`jsonschema` encoding): Foxglove's Map, 3D, Image and Log panels read them.

Only the samples of the types that derive anything are decoded (positions, pictures, text,
joints, their configs, and any type with latitude and longitude); a sample that does not
decode is recorded as it came and derives nothing (counted)."""
from __future__ import annotations

import json
from typing import Any, Callable

from rapidgen.foxglove.derive import Deriver
from rapidgen.foxglove.schemas import SCHEMAS, schema_bytes
from rapidgen.record.mcapfile import ChannelInfo

DERIVING = {"PositionConfig", "JointConfig", "PositionSample", "ImageSensorSample", "TextMessage", "JointSample"}
ENCODINGS = ("jsonschema", "json")


def derives(type_name: str, cls: Any) -> bool:
    """Whether samples of this type derive anything (or configure what does)."""
    if type_name.rpartition("::")[2] in DERIVING:
        return True
    fields = getattr(cls, "__annotations__", None) or {}
    return "latitude" in fields and "longitude" in fields


def frames_of(bindings: list) -> dict[tuple[str, str], tuple[str, str]]:
    """(partition, PositionSample topic) -> (frame, pose encoding), from the descriptors."""
    out: dict[tuple[str, str], tuple[str, str]] = {}
    for b in bindings[1:]:
        asset = b.tables["ASSET"]
        partition = asset.get("partition", asset["name"])
        for t in b.tables.get("TELEMETRY", ()) or ():
            if isinstance(t, dict) and t.get("kind") == "position" and t.get("frame"):
                topic = (t.get("topics") or {}).get("sample")
                if topic:
                    out[(partition, topic)] = (str(t["frame"]), str(t.get("pose_encoding") or "RAPID_ROT_NONE"))
    return out


class DerivedWriter:
    """Decodes the samples that derive something and writes the derived messages into the sink."""

    def __init__(self, sink, bindings: list) -> None:
        self.sink = sink
        self.deriver = Deriver(frames_of(bindings))
        self.messages = 0
        self.undecodable = 0
        self._wanted: dict[str, Any] = {}  # type name -> its class when it derives anything, else None
        self._channels: dict[tuple[str, str], ChannelInfo] = {}
        for name in SCHEMAS:
            sink.schema(name, schema_bytes(name).decode("utf-8"))

    def take(self, channel: ChannelInfo, data: bytes, received_ns: int, type_class: Callable[[str], Any]) -> None:
        """One recorded sample: decoded and derived when its type derives anything."""
        got = self._wanted.get(channel.type_name)
        if got is None:
            cls = type_class(channel.type_name)
            got = self._wanted[channel.type_name] = cls if cls is not None and derives(channel.type_name, cls) else None
        if got is not None:
            self.sample(channel, got, data, received_ns)

    def sample(self, channel: ChannelInfo, cls: Any, data: bytes, received_ns: int) -> None:
        try:
            value = cls.deserialize(data)
        except Exception:  # bytes the type does not decode (recorded as they came)
            self.undecodable += 1
            return
        for d in self.deriver.feed(channel.topic, channel.partition, channel.type_name, value, received_ns):
            key = (d.topic, d.schema)
            ch = self._channels.get(key)
            if ch is None:
                if len(self._channels) >= 4096:
                    continue
                ch = self._channels[key] = ChannelInfo(d.topic, d.schema, channel.partition,
                                                       {"role": "foxglove", "derived_from": d.source}, ENCODINGS)
            t = d.message["timestamp"]
            body = json.dumps(d.message, separators=(",", ":"), ensure_ascii=True).encode("ascii")
            self.sink.write(ch, received_ns, t["sec"] * 1_000_000_000 + t["nsec"], body)
            self.messages += 1
