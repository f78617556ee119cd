"""The DDS side of `rapidgen record`: rapidgen.live's discovery finds every writer of a RAPID
type (the shipped IDL's, or an --asset's extension types); for each one a reader in its
partition asks for the reliability and durability the writer offers (a healthy writer
offers its RapidQosLibrary profile: configs, acks and text durable, so a recorder that
starts late still gets them; a writer off its profile is recorded too: spy says which).

Samples are taken raw (cyclonedds' ddspy_take): the CDR bytes as received, never decoded
or re-encoded, with the writer's source timestamp. Two readers of one topic and partition
with other QoS may both match a writer; each writer's samples are kept from one reader
only (the one opened for what it offers), so nothing is recorded twice.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Callable

from rapidgen.record.mcapfile import ChannelInfo

DURABLE = ("TransientLocal", "Transient", "Persistent")
DEPTH = 4096  # reader history per instance: ~0.4 s of a 10k/s writer between two takes (docs/record.md)
TAKE = 256  # samples per take
MAX_READERS = 512


def role_of(type_name: str) -> str:
    """RAPID's type naming: *Config, *State, *Sample, Command, Ack; else message."""
    name = type_name.rpartition("::")[2]
    for suffix, role in (("Config", "config"), ("State", "state"), ("Sample", "sample")):
        if name.endswith(suffix):
            return role
    return {"Command": "command", "Ack": "ack"}.get(name, "message")


@dataclass
class Stream:
    channel: ChannelInfo
    reader: Any
    offer: tuple[bool, bool]  # (reliable, durable): the writers whose samples this reader keeps
    owners: dict[int, bool] = field(default_factory=dict)  # publication handle -> ours
    count: int = 0
    bytes: int = 0
    window: list[int] = field(default_factory=lambda: [0, 0])  # counts at the last two rate ticks


class Recorder:
    def __init__(self, domain: int, bindings: list, partitions: set[str] | None,
                 schema_of: Callable[[str], str | None], sink, roles: dict[str, str]) -> None:
        """bindings: base first, then --asset ones; partitions: record only these (None:
        every partition); schema_of(type name) -> IDL text; roles: topic -> role."""
        from cyclonedds.domain import DomainParticipant

        from rapidgen.live.discovery import Discovery
        from rapidgen.live.teardown import delete_participant
        self.dp: DomainParticipant | None = DomainParticipant(domain)
        try:
            self.discovery = Discovery(self.dp)
        except BaseException:  # no half-made participant left running (close())
            delete_participant(self.dp)
            raise
        self.bindings, self.partitions, self.schema_of, self.sink, self.roles = \
            bindings, partitions, schema_of, sink, roles
        self.streams: dict[tuple[str, str, bool, bool], Stream] = {}
        self.skipped: dict[tuple[str, str], str] = {}  # (topic, type) -> why not recorded
        self._topics: dict[str, Any] = {}
        self._subscribers: dict[str, Any] = {}
        self._done: dict[str, object] = {}
        self._seq = 0
        self.derived: Any = None  # rapidgen.record.derived.DerivedWriter with --foxglove

    def type_class(self, type_name: str):
        from rapidgen.live.bindings import find_type_class
        return find_type_class(self.bindings, type_name)

    def _subscriber(self, partition: str):
        if partition not in self._subscribers:
            from cyclonedds.qos import Policy, Qos
            from cyclonedds.sub import Subscriber
            self._subscribers[partition] = Subscriber(self._dp(), qos=Qos(Policy.Partition([partition])))
        return self._subscribers[partition]

    def _skip(self, topic: str, type_name: str, why: str) -> None:
        if len(self.skipped) < 4096:
            self.skipped.setdefault((topic, type_name), why)

    def declared(self, qos, partition: str) -> None:
        """Readers for every topic an asset's descriptor declares, with its profile's QoS, before
        any writer is seen: a short-lived writer (a commander) is matched from its start."""
        import json

        from rapidgen.live.discovery import QosSummary
        with open(qos.topics_file, encoding="utf-8") as fh:
            entries = json.load(fh).get("topics", [])
        for e in entries:
            q = QosSummary.of(qos.reader(e["topic"]))
            self._open(e["topic"], e["type"], partition, (q.reliability == "Reliable", q.durability in DURABLE))

    def _open(self, topic: str, type_name: str, partition: str, offer: tuple[bool, bool]) -> None:
        """A reader of topic in partition keeping the samples of the writers that offer `offer`
        (reliable, durable)."""
        from cyclonedds.qos import Policy, Qos
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic
        key = (topic, partition) + offer
        if key in self.streams:
            return
        type_name = type_name.replace(".", "::")
        cls = self.type_class(type_name)
        if cls is None:
            self._skip(topic, type_name, "no bindings for its type (give the asset's descriptor with --asset)")
            return
        if len(self.streams) >= MAX_READERS:
            self._skip(topic, type_name, f"reader cap ({MAX_READERS}) reached")
            return
        try:
            if topic not in self._topics:
                self._topics[topic] = Topic(self._dp(), topic, cls)
            qos = Qos(Policy.Reliability.Reliable(1_000_000_000) if offer[0] else Policy.Reliability.BestEffort,
                      Policy.Durability.TransientLocal if offer[1] else Policy.Durability.Volatile,
                      Policy.History.KeepLast(DEPTH))
            reader = DataReader(self._subscriber(partition), self._topics[topic], qos=qos)
        except Exception as exc:  # e.g. one topic name written with two types
            self._skip(topic, type_name, f"cannot read it: {type(exc).__name__}")
            return
        idl = self.schema_of(type_name)
        if idl is not None:
            self.sink.schema(type_name, idl)
        meta = {"reliability": "Reliable" if offer[0] else "BestEffort",
                "durability": "TransientLocal" if offer[1] else "Volatile",
                "role": self.roles.get(topic) or role_of(type_name)}
        self.streams[key] = Stream(ChannelInfo(topic, type_name, partition, meta), reader, offer)
        self.sink.channel(self.streams[key].channel)  # in the file even if it never sends

    def discover(self) -> None:
        """Readers for the writers discovered since the last call."""
        self.discovery.poll()
        eps = self.discovery.endpoints
        if len(self._done) > 2 * len(eps) + 1024:
            self._done = {k: v for k, v in self._done.items() if eps.get(k) is v}
        for ep in list(eps.values()):
            if self._done.get(ep.key) is ep or ep.kind != "writer":
                continue
            self._done[ep.key] = ep
            for part in ep.partitions:
                if "*" in part or "?" in part or (self.partitions is not None and part not in self.partitions):
                    continue
                self._open(ep.topic, ep.type_name, part,
                           (ep.qos.reliability == "Reliable", ep.qos.durability in DURABLE))

    def _ours(self, st: Stream, handle: int) -> bool:
        """Whether this reader keeps the writer's samples (it was opened for what it offers)."""
        got = st.owners.get(handle)
        if got is None:
            try:
                data = st.reader.get_matched_publication_data(handle)
            except Exception:
                data = None
            if data is None:
                return True  # gone already: keep what it sent
            from rapidgen.live.discovery import QosSummary
            q = QosSummary.of(data.qos)
            got = (q.reliability == "Reliable", q.durability in DURABLE) == st.offer
            if len(st.owners) > 4096:
                st.owners.clear()
            st.owners[handle] = got
        return got

    def take(self) -> int:
        """Take every reader's samples into the sink; how many were written."""
        from cyclonedds._clayer import ddspy_take
        from cyclonedds.core import InstanceState, SampleState, ViewState
        mask = SampleState.Any | ViewState.Any | InstanceState.Any
        written = 0
        for st in self.streams.values():
            while True:
                raw = ddspy_take(st.reader._ref, mask, TAKE)
                if isinstance(raw, int) or not raw:
                    break
                now = time.time_ns()
                for data, info in raw:
                    if not info.valid_data or not self._ours(st, info.publication_handle):
                        continue
                    self._seq += 1
                    self.sink.write(st.channel, now, int(info.source_timestamp or now), bytes(data), self._seq)
                    if self.derived is not None:
                        self.derived.take(st.channel, bytes(data), now, self.type_class)
                    st.count += 1
                    st.bytes += len(data)
                    written += 1
                if len(raw) < TAKE:
                    break
        return written

    def _dp(self):
        if self.dp is None:
            raise RuntimeError("closed")
        return self.dp

    def close(self) -> None:
        """Delete our participant and all in it now (rapidgen/live/teardown.py: left to the
        collector, its domain's threads outlived the interpreter). Nothing is taken after."""
        from rapidgen.live.teardown import delete_participant
        self.streams.clear()
        self._topics.clear()
        self._subscribers.clear()
        dp, self.dp = self.dp, None
        delete_participant(dp)
