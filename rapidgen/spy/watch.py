"""Joining the domain and reading what flows: rapidgen.live's discovery (participants,
endpoints, announced QoS) plus, for every RAPID writer seen, a reader of its topic in its
partition asking for what the writer offers (so it matches, and gets a durable writer's
history as a late joiner). Samples are kept with their writer and source timestamp."""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic

DURABLE = ("TransientLocal", "Transient", "Persistent")


@dataclass
class Seen:
    at: float  # time.monotonic() at arrival
    stamp: float | None  # the writer's source timestamp [s], when DDS gives it
    writer: str | None  # the writer's GUID, when DDS says which
    sample: object


@dataclass
class Stream:
    """One of our readers: a topic in a partition with one writer QoS."""
    topic: str
    partition: str
    type_name: str
    reader: DataReader[Any]
    created: float
    seen: list[Seen] = field(default_factory=list)
    _handles: dict[int, str] = field(default_factory=dict)

    def matched(self) -> set[str]:
        """GUIDs of the writers this reader matched (a RAPID-named writer missing here while
        its QoS allows a match has another layout)."""
        out: set[str] = set()
        for h in self.reader.get_matched_publications():
            try:
                data = self.reader.get_matched_publication_data(h)
            except Exception:  # it left between the two calls
                continue
            if data is not None:  # None: it left between the two calls
                out.add(str(data.key))
        return out

    def writer_of(self, handle: int) -> str | None:
        if handle not in self._handles:
            try:
                data = self.reader.get_matched_publication_data(handle)
            except Exception:
                return None
            if data is None:
                return None
            self._handles[handle] = str(data.key)
        return self._handles[handle]


class Watcher:
    def __init__(self, domain: int, bindings: list, partitions: list[str] | None = None,
                 keep: int = 2000) -> None:
        from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsPublication
        from cyclonedds.domain import DomainParticipant

        from rapidgen.live.discovery import Discovery
        self.domain = domain
        self.bindings = bindings
        self.partitions = partitions or []
        self.keep = keep
        self.dp: DomainParticipant | None = DomainParticipant(domain)
        self.discovery = Discovery(self.dp)
        self._types = BuiltinDataReader(self.dp, BuiltinTopicDcpsPublication)  # type ids, for layout diffs
        self.type_ids: dict[str, object] = {}
        self.streams: dict[tuple[str, str, bool, bool], Stream] = {}
        self.undecodable: set[tuple[str, str]] = set()  # (topic, type name) we have no type for
        self._topics: dict[str, Topic[Any]] = {}
        self._subscribers: dict[str, Subscriber] = {}
        self.started = time.monotonic()
        self.started_wall = time.time()

    # ---- types ---------------------------------------------------------------------------
    def type_class(self, type_name: str):
        scoped = type_name.replace(".", "::")
        for b in self.bindings:
            try:
                return b.type_class(scoped)
            except (KeyError, AttributeError, ImportError):
                continue
        return None

    def wanted(self, partitions: tuple[str, ...]) -> bool:
        return not self.partitions or any(p in self.partitions or p == "*" for p in partitions)

    # ---- readers -------------------------------------------------------------------------
    def _participant(self) -> DomainParticipant:
        if self.dp is None:
            raise RuntimeError("the watcher is closed")
        return self.dp

    def _subscriber(self, partition: str) -> Subscriber:
        if partition not in self._subscribers:
            from cyclonedds.qos import Policy, Qos
            from cyclonedds.sub import Subscriber
            self._subscribers[partition] = Subscriber(self._participant(), qos=Qos(Policy.Partition([partition])))
        return self._subscribers[partition]

    def _stream(self, ep, partition: str) -> Stream | None:
        from cyclonedds.qos import Policy, Qos
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic
        reliable = ep.qos.reliability == "Reliable"
        durable = ep.qos.durability in DURABLE
        key = (ep.topic, partition, reliable, durable)
        if key in self.streams:
            return self.streams[key]
        cls = self.type_class(ep.type_name)
        if cls is None:
            self.undecodable.add((ep.topic, ep.type_name))
            return None
        try:
            if ep.topic not in self._topics:
                self._topics[ep.topic] = Topic(self._participant(), ep.topic, cls)
            qos = Qos(Policy.Reliability.Reliable(100_000_000) if reliable else Policy.Reliability.BestEffort,
                      Policy.Durability.TransientLocal if durable else Policy.Durability.Volatile,
                      Policy.History.KeepLast(256))
            reader: DataReader[Any] = DataReader(self._subscriber(partition), self._topics[ep.topic], qos=qos)
        except Exception:  # e.g. one topic name used with two types: shown, not read
            self.undecodable.add((ep.topic, ep.type_name))
            return None
        self.streams[key] = Stream(ep.topic, partition, ep.type_name, reader, time.monotonic())
        return self.streams[key]

    def step(self) -> None:
        """Take discovery news, open readers for new writers, take their samples."""
        self.discovery.poll()
        for s in self._types.take(N=512):
            tid = getattr(s, "type_id", None)
            if tid is not None:
                self.type_ids[str(s.key)] = tid
        for ep in list(self.discovery.endpoints.values()):
            if ep.kind == "writer" and self.wanted(ep.partitions):
                for part in ep.partitions:
                    if "*" not in part and "?" not in part:
                        self._stream(ep, part)
        now = time.monotonic()
        for st in self.streams.values():
            for s in st.reader.take(N=512):
                if s is None or type(s).__name__.startswith("Invalid"):
                    continue
                info = getattr(s, "sample_info", None)
                stamp = getattr(info, "source_timestamp", None)
                writer = st.writer_of(info.publication_handle) if info is not None else None
                st.seen.append(Seen(now, stamp / 1e9 if stamp else None, writer, s))
            if len(st.seen) > self.keep:
                del st.seen[: len(st.seen) - self.keep]

    def run_for(self, seconds: float, step: float = 0.05, until=None) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.step()
            if until is not None and until(self):
                return
            time.sleep(step)
        self.step()

    def seen(self, topic: str, partition: str) -> list[Seen]:
        out = [s for st in self.streams.values() if st.topic == topic and st.partition == partition for s in st.seen]
        return sorted(out, key=lambda s: (s.stamp or 0.0, s.at))

    def close(self) -> None:
        self.streams.clear()
        self.dp = None
