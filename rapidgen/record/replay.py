"""Republishing a recording (`rapidgen replay`): every config first (durable writers, so a
reader that joins later still gets them), then the other messages at their recorded times
(log time, scaled by --rate), each channel from its own writer with the recorded
reliability and durability, in its recorded partition or the one chosen.

A recording is a file from anywhere: each message is decoded with its type's bindings
before it is sent (a message that does not decode is skipped and counted), and the bytes
sent are the recorded ones, not a re-encoding.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Callable

CONFIG_DEPTH = 8  # a durable writer's history per instance (RAPID's ack writer keeps 8 too)
SAMPLE_DEPTH = 64
# The configs of the window are read first and held until they are sent: their bytes plus
# PER_CONFIG each (the key, the message object and its tuple: about 600 bytes measured).
MAX_CONFIG_BYTES = 64 << 20
PER_CONFIG = 1024


@dataclass
class Out:
    """One recorded channel's writer."""
    topic: str
    type_name: str
    partition: str
    cls: Any
    writer: Any = None
    sent: int = 0
    skipped: int = 0  # did not decode
    first_error: str = ""


@dataclass
class Plan:
    start: int  # ns: the recording's first log time
    begin: int  # ns: first log time replayed (start + --from)
    end: int | None  # ns: last log time replayed (start + --to)
    topics: set[str] | None
    rate: float
    partition: str | None
    outs: dict[tuple[str, str, str], Out | None] = field(default_factory=dict)  # channel -> writer (None: not replayed)
    not_replayed: dict[str, str] = field(default_factory=dict)  # "[partition] topic" -> why


def is_config(channel) -> bool:
    meta = channel.metadata
    return meta.get("role") == "config" or (meta.get("role") is None and meta.get("dds_type", "").endswith("Config"))


class Replayer:
    def __init__(self, domain: int, type_class: Callable[[str], Any], plan: Plan) -> None:
        from cyclonedds.domain import DomainParticipant
        self.dp: DomainParticipant | None = DomainParticipant(domain)
        self.type_class, self.plan = type_class, plan
        self._topics: dict[str, Any] = {}
        self._publishers: dict[str, Any] = {}

    def out(self, channel) -> Out | None:
        """The channel's writer, made on first use; None when it is not replayed."""
        from rapidgen.textsafe import visible
        meta = channel.metadata
        type_name = meta.get("dds_type", "")
        key = (channel.topic, meta.get("partition", ""), type_name)  # channel ids differ between files
        if key in self.plan.outs:
            return self.plan.outs[key]
        partition = self.plan.partition if self.plan.partition is not None else meta.get("partition", "")
        where = f"[{visible(meta.get('partition', ''))}] {visible(channel.topic)}"
        got: Out | None = None
        if self.plan.topics is not None and channel.topic not in self.plan.topics:
            pass
        elif channel.message_encoding != "cdr":
            self.plan.not_replayed[where] = f"message encoding {visible(channel.message_encoding)!r}, not cdr"
        else:
            cls = self.type_class(type_name)
            if cls is None:
                self.plan.not_replayed[where] = (f"no bindings for {visible(type_name) or 'its type'} "
                                                 "(give the asset's descriptor with --asset)")
            else:
                got = self._writer(Out(channel.topic, type_name, partition, cls), meta)
                if got is None:
                    self.plan.not_replayed[where] = "DDS refused its topic or writer (a name it cannot use, or a topic " \
                        "of another type)"
        self.plan.outs[key] = got
        return got

    def _writer(self, out: Out, meta: dict) -> Out | None:
        from cyclonedds.pub import DataWriter, Publisher
        from cyclonedds.qos import Policy, Qos
        from cyclonedds.topic import Topic
        reliable = meta.get("reliability", "Reliable") == "Reliable"
        durable = meta.get("durability") == "TransientLocal"
        try:
            if out.topic not in self._topics:
                self._topics[out.topic] = Topic(self._dp(), out.topic, out.cls)
            elif self._topics[out.topic].data_type is not out.cls:
                return None
            if out.partition not in self._publishers:
                self._publishers[out.partition] = Publisher(self._dp(), qos=Qos(Policy.Partition([out.partition])))
            qos = Qos(Policy.Reliability.Reliable(1_000_000_000) if reliable else Policy.Reliability.BestEffort,
                      Policy.Durability.TransientLocal if durable else Policy.Durability.Volatile,
                      Policy.History.KeepLast(CONFIG_DEPTH if durable else SAMPLE_DEPTH))
            out.writer = DataWriter(self._publishers[out.partition], self._topics[out.topic], qos=qos)
        except Exception:  # Cyclone refused the topic or writer (e.g. a type name it cannot use)
            return None
        return out

    def send(self, out: Out, data: bytes) -> bool:
        """The recorded bytes, once they decode as the channel's type."""
        from cyclonedds._clayer import ddspy_write
        from rapidgen.textsafe import visible
        try:
            out.cls.deserialize(data)
        except Exception as exc:  # a damaged or foreign message: skipped, counted
            out.skipped += 1
            if not out.first_error:
                out.first_error = visible(f"{type(exc).__name__}: {exc}"[:160])
            return False
        if len(data) % 4:
            data = data + b"\0" * (4 - len(data) % 4)
        if ddspy_write(out.writer._ref, data) < 0:
            out.skipped += 1
            out.first_error = out.first_error or "the DDS write failed"
            return False
        out.sent += 1
        return True

    def _dp(self):
        if self.dp is None:
            raise RuntimeError("closed")
        return self.dp

    def close(self) -> None:
        """Delete our participant and all in it now (rapidgen/live/teardown.py: left to the
        collector, its domain's threads outlived the interpreter). Nothing is sent after."""
        from rapidgen.live.teardown import delete_participant
        self._topics.clear()
        self._publishers.clear()
        self.plan.outs.clear()
        dp, self.dp = self.dp, None
        delete_participant(dp)


def in_window(plan: Plan, log_time: int) -> bool:
    return log_time >= plan.begin and (plan.end is None or log_time <= plan.end)


def pace(plan: Plan, wall_start: float, log_time: int, stop) -> bool:
    """Wait until the message's time has come (False: asked to stop)."""
    due = wall_start + (log_time - plan.begin) / 1e9 / plan.rate
    while True:
        left = due - time.monotonic()
        if left <= 0:
            return True
        if stop.wait(min(left, 0.2)):
            return False
