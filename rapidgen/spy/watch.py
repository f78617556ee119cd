"""Joining the domain and reading what flows: rapidgen.live's discovery (participants,
endpoints, announced QoS) plus, for every RAPID writer seen, a reader of its topic in its
partition asking for what the writer offers (so it matches, and gets a durable writer's
history as a late joiner). Samples are kept with their writer and source timestamp.

The network is untrusted (any participant in a partition writes any topic with any bytes),
so every take goes through rapid_runtime.untrusted.GuardedReader (a sample that does not decode
is dropped alone and counted against its writer; a durable config republished with the
same bytes is decoded once), and what is kept is bounded by the caps below, which
docs/spy.md lists; what they leave out is said in the output (`Watcher.limits`).
"""
from __future__ import annotations

import collections
import heapq
import itertools
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from rapid_runtime.untrusted import GuardedReader

if TYPE_CHECKING:
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic

DURABLE = ("TransientLocal", "Transient", "Persistent")

# ---- caps (docs/spy.md, "Limits") ------------------------------------------------------------
MAX_PARTITIONS = 64  # partitions read, besides those named by --partition or an --asset
MAX_PARTITIONS_PER_WRITER = 16  # of one writer's partitions, the first 16 are read
MAX_STREAMS = 256  # our readers, in all, besides those of the declared partitions...
MAX_DECLARED_STREAMS = 256  # ...which have as many each, of their own (a flood elsewhere cannot take them)
MAX_WRITERS_PER_STREAM = 16  # writers kept apart per reader; samples of later ones share one pool
KEEP_PER_WRITER = 256  # arrival records kept per writer (and for the pool) per reader: the newest
BIG_SAMPLE = 256 << 10  # a sample larger than this on the wire is big...
BIG_BUDGET = 16 << 20  # ...and big latest samples are kept up to this many wire bytes in all
REMEMBER_BYTES = 16 << 20  # per config reader: wire bytes remembered to decode a republished config once
CONFIG_DEPTH = 1  # our readers' history: a config reader needs only each instance's latest,
SAMPLE_DEPTH = 64  # others keep up between two takes (every 50 ms)
BATCH = 32  # samples per take (config readers: CONFIG_BATCH, a config may be 4.6 MB)
CONFIG_BATCH = 2
STEP_BUDGET = 0.5  # seconds one step spends taking; what is left waits for the next step
MAX_NAMED_UNREAD = 4096  # partitions not read are remembered by name up to this many, then counted
MAX_CMD_IDS = 8192  # cmdIds of commands seen, remembered to judge acks (SPY-ACK-01)
_POOL = "\0pool"  # the key of a stream's shared pool of records


@dataclass(slots=True)
class Seen:
    """One sample as kept: when, from whom, the header fields the diagnoses read, and the
    decoded sample itself only while it is its reader's latest (None afterwards)."""
    seq: int  # arrival order across all readers
    at: float  # time.monotonic() at arrival
    stamp: float | None  # the writer's source timestamp [s], when DDS gives it
    writer: str | None  # the writer's GUID, when DDS says which
    sample: object | None
    src: str = ""  # hdr.srcName
    asset: str = ""  # hdr.assetName
    serial: int | None = None  # hdr.serial
    time_stamp: int | None = None  # hdr.timeStamp
    cmd_id: str | None = None  # Command/Ack cmdId
    size: int = 0  # wire bytes


@dataclass
class Stream:
    """One of our readers: a topic in a partition with one writer QoS."""
    topic: str
    partition: str
    type_name: str
    reader: DataReader[Any]
    created: float
    guard: GuardedReader
    config: bool = False  # a durable config reader (history 1, small batches, dedupe)
    by_writer: dict[str, collections.deque[Seen]] = field(default_factory=dict)
    latest: Seen | None = None  # the newest sample; its .sample is kept (within BIG_BUDGET)
    count: int = 0  # samples taken and decoded, in all
    released: int = 0  # records let go by KEEP_PER_WRITER
    pooled: set[str] = field(default_factory=set)  # writers past MAX_WRITERS_PER_STREAM (up to 1024 named)
    not_kept: int = 0  # latest samples not kept whole: BIG_BUDGET was spent
    _handles: dict[int, str] = field(default_factory=dict)

    @property
    def seen(self) -> list[Seen]:
        """The records kept, in arrival order."""
        return list(heapq.merge(*self.by_writer.values(), key=lambda s: s.seq))

    def of_writer(self, writer: str) -> list[Seen]:
        if writer in self.by_writer:
            return list(self.by_writer[writer])
        return [s for s in self.by_writer.get(_POOL, ()) if s.writer == writer]

    def keep(self, rec: Seen) -> None:
        key = rec.writer or ""
        if key not in self.by_writer:
            if len(self.by_writer) >= MAX_WRITERS_PER_STREAM:
                if len(self.pooled) < 1024:
                    self.pooled.add(key)
                key = _POOL
            self.by_writer.setdefault(key, collections.deque())
        q = self.by_writer[key]
        if len(q) >= KEEP_PER_WRITER:
            q.popleft()
            self.released += 1
        q.append(rec)
        self.count += 1

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
            if len(self._handles) >= 4096:
                self._handles.clear()
            self._handles[handle] = str(data.key)
        return self._handles[handle]


def _text(value, limit: int = 256) -> str:
    return value[:limit] if isinstance(value, str) else ""


def _int(value) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None


class Watcher:
    def __init__(self, domain: int, bindings: list, partitions: list[str] | None = None,
                 declared: list[str] | None = None, topics: set[str] | None = None) -> None:
        """partitions: read only these (--partition); declared: partitions always read
        (the --asset descriptors'), besides MAX_PARTITIONS others; topics: read only these."""
        from cyclonedds.domain import DomainParticipant

        from rapidgen.live.discovery import Discovery
        from rapidgen.live.teardown import delete_participant
        self.domain = domain
        self.bindings = bindings
        self.partitions = partitions or []
        self.declared = set(self.partitions) | set(declared or [])
        self.topics = topics
        self.dp: DomainParticipant | None = DomainParticipant(domain)
        try:
            self.discovery = Discovery(self.dp)
        except BaseException:  # no half-made participant left running (close())
            delete_participant(self.dp)
            raise
        self.streams: dict[tuple[str, str, bool, bool], Stream] = {}
        self.undecodable: set[tuple[str, str]] = set()  # (topic, type name) we have no type for
        self.read_partitions: set[str] = set()  # partitions we read (declared ones and up to MAX_PARTITIONS)
        self.unread_partitions: set[str] = set()  # seen, not read (up to MAX_NAMED_UNREAD names)
        self.unread_more = False  # more partitions than MAX_NAMED_UNREAD were not read
        self.capped: collections.Counter[str] = collections.Counter()  # what a cap left out -> how many
        self.big_bytes = 0  # wire bytes of the big latest samples kept
        self.cmd_ids: dict[str, None] = {}  # cmdIds of the commands seen (the newest MAX_CMD_IDS), for acks
        self.tap: Callable[[Stream, Seen], None] | None = None  # sees every sample (echo)
        self._topics: dict[str, Topic[Any]] = {}
        self._subscribers: dict[str, Subscriber] = {}
        self._done: dict[str, object] = {}  # endpoint key -> the Endpoint its streams were opened for
        self._seq = itertools.count()
        self._turn = 0
        self.started = time.monotonic()
        self.started_wall = time.time()

    @property
    def type_ids(self) -> dict[str, object]:
        return self.discovery.type_ids

    # ---- types ---------------------------------------------------------------------------
    def type_class(self, type_name: str):
        from rapidgen.live.bindings import find_type_class
        return find_type_class(self.bindings, type_name)

    def wanted(self, partitions: tuple[str, ...]) -> bool:
        return not self.partitions or any(p in self.partitions or p == "*" for p in partitions)

    def read(self, partition: str) -> bool:
        """We read this partition (declared, or one of the first MAX_PARTITIONS others)."""
        return partition in self.read_partitions

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

    def _admit(self, partition: str) -> bool:
        if partition in self.read_partitions:
            return True
        if partition in self.declared or len(self.read_partitions - self.declared) < MAX_PARTITIONS:
            self.read_partitions.add(partition)
            self.unread_partitions.discard(partition)
            return True
        self._unread(partition)
        return False

    def _unread(self, partition: str) -> None:
        if partition not in self.unread_partitions:
            if len(self.unread_partitions) < MAX_NAMED_UNREAD:
                self.unread_partitions.add(partition)
            else:
                self.unread_more = True

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
            if len(self.undecodable) < 4096:
                self.undecodable.add((ep.topic, ep.type_name))
            return None
        if partition in self.declared:
            if sum(1 for k in self.streams if k[1] == partition) >= MAX_DECLARED_STREAMS:
                self.capped[f"readers (topic, QoS) of the declared partition {partition!r} not opened"] += 1
                return None
        elif sum(1 for k in self.streams if k[1] not in self.declared) >= MAX_STREAMS:
            self.capped["readers (topic, partition, QoS) not opened"] += 1
            return None
        config = durable and ep.type_name.endswith("Config")
        try:
            if ep.topic not in self._topics:
                self._topics[ep.topic] = Topic(self._participant(), ep.topic, cls)
            qos = Qos(Policy.Reliability.Reliable(100_000_000) if reliable else Policy.Reliability.BestEffort,
                      Policy.Durability.TransientLocal if durable else Policy.Durability.Volatile,
                      Policy.History.KeepLast(CONFIG_DEPTH if config else SAMPLE_DEPTH))
            reader: DataReader[Any] = DataReader(self._subscriber(partition), self._topics[ep.topic], qos=qos)
        except Exception:  # e.g. one topic name used with two types: shown, not read
            self.undecodable.add((ep.topic, ep.type_name))
            return None
        guard = GuardedReader(reader, dedupe=config, batch=CONFIG_BATCH if config else BATCH,
                              remember_bytes=REMEMBER_BYTES)
        self.streams[key] = Stream(ep.topic, partition, ep.type_name, reader, time.monotonic(), guard, config)
        return self.streams[key]

    def _open(self) -> None:
        """Readers for the writers discovered since the last step."""
        eps = self.discovery.endpoints
        if len(self._done) > 2 * len(eps) + 1024:
            self._done = {k: v for k, v in self._done.items() if eps.get(k) is v}
        for ep in list(eps.values()):
            if self._done.get(ep.key) is ep:
                continue
            self._done[ep.key] = ep
            if ep.kind != "writer" or not self.wanted(ep.partitions) \
                    or (self.topics is not None and ep.topic not in self.topics):
                continue
            parts = [p for p in ep.partitions if "*" not in p and "?" not in p
                     and (not self.partitions or p in self.partitions)]
            parts.sort(key=lambda p: p not in self.declared)  # declared partitions first
            for i, part in enumerate(parts):
                if i >= MAX_PARTITIONS_PER_WRITER and part not in self.read_partitions:
                    self._unread(part)
                elif self._admit(part):
                    self._stream(ep, part)

    def step(self) -> None:
        """Take discovery news, open readers for new writers, take their samples (for at
        most STEP_BUDGET seconds; the readers take turns being first)."""
        self.discovery.poll()
        self._open()
        streams = list(self.streams.values())
        if not streams:
            return
        self._turn = (self._turn + 1) % len(streams)
        deadline = time.monotonic() + STEP_BUDGET
        for st in streams[self._turn:] + streams[:self._turn]:
            if time.monotonic() >= deadline:
                break
            while time.monotonic() < deadline:
                before = st.guard.dropped
                got = st.guard.take()
                for s in got:
                    self._arrived(st, s)
                if len(got) + st.guard.dropped - before < st.guard.batch:
                    break

    def _arrived(self, st: Stream, s) -> None:
        info = getattr(s, "sample_info", None)
        stamp = getattr(info, "source_timestamp", None)
        writer = st.writer_of(info.publication_handle) if info is not None else None
        hdr = getattr(s, "hdr", None)
        cmd_id = getattr(s, "cmdId", None)
        rec = Seen(next(self._seq), time.monotonic(), stamp / 1e9 if stamp else None, writer, s,
                   _text(getattr(hdr, "srcName", "")), _text(getattr(hdr, "assetName", "")),
                   _int(getattr(hdr, "serial", None)), _int(getattr(hdr, "timeStamp", None)),
                   _text(cmd_id) if isinstance(cmd_id, str) else None, int(getattr(s, "wire_size", 0)))
        st.keep(rec)
        if rec.cmd_id is not None and st.type_name.endswith("::Command"):
            self.cmd_ids.pop(rec.cmd_id, None)
            self.cmd_ids[rec.cmd_id] = None
            if len(self.cmd_ids) > MAX_CMD_IDS:
                del self.cmd_ids[next(iter(self.cmd_ids))]
        if self.tap is not None:
            self.tap(st, rec)
        old = st.latest
        if old is not None:
            if old.sample is not None and old.size > BIG_SAMPLE:
                self.big_bytes -= old.size
            old.sample = None
        if rec.size > BIG_SAMPLE:
            if self.big_bytes + rec.size > BIG_BUDGET:
                rec.sample = None
                st.not_kept += 1
            else:
                self.big_bytes += rec.size
        st.latest = rec

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

    def latest(self, topic: str, partition: str) -> Seen | None:
        """The newest sample of topic in partition still kept whole."""
        got = [st.latest for st in self.streams.values() if st.topic == topic and st.partition == partition
               and st.latest is not None and st.latest.sample is not None]
        return max(got, key=lambda s: (s.stamp or 0.0, s.at), default=None)

    # ---- what was dropped or left out ------------------------------------------------------
    def dropped(self) -> list[dict]:
        """Undecodable samples, per reader and writer: partition, topic, writer (GUID and
        participant), count, first error."""
        out = []
        for st in self.streams.values():
            for handle, d in st.guard.drops.items():
                guid = st.writer_of(handle) if handle else None
                ep = self.discovery.endpoints.get(guid) if guid else None
                out.append({"partition": st.partition, "topic": st.topic, "writer": guid or d.writer,
                            "participant": ep.participant if ep is not None else None, "count": d.count,
                            "error": d.first_error})
        return out

    def limits(self) -> list[str]:
        """What the caps left out or what was not kept, one line each."""
        out = list(self.discovery.notes())
        if self.unread_partitions:
            n = len(self.unread_partitions)
            names = ", ".join(repr(p) for p in sorted(self.unread_partitions)[:3])
            out.append(f"{'more than ' if self.unread_more else ''}{n} partition(s) not read (caps: {MAX_PARTITIONS} "
                       f"besides those named with --partition/--asset, {MAX_PARTITIONS_PER_WRITER} per writer), "
                       f"e.g. {names}")
        out += [f"{n} {what} (cap {MAX_STREAMS})" for what, n in self.capped.items()]
        for st in self.streams.values():
            where = f"[{st.partition}] {st.topic}"
            if st.pooled:
                out.append(f"{where}: {len(st.pooled)}{'+' if len(st.pooled) >= 1024 else ''} writer(s) past "
                           f"{MAX_WRITERS_PER_STREAM} share one record pool")
            if st.not_kept:
                out.append(f"{where}: {st.not_kept} big sample(s) not kept whole (cap {BIG_BUDGET >> 20} MiB of "
                           f"samples over {BIG_SAMPLE >> 10} KiB)")
            if st.guard.reused:
                out.append(f"{where}: {st.guard.reused} republished config(s) with the same bytes decoded once")
        return out

    def close(self) -> None:
        """Delete our participant and all in it now (rapidgen/live/teardown.py: left to the
        collector, its domain's threads outlived the interpreter). Nothing is read after."""
        from rapidgen.live.teardown import delete_participant
        self.streams.clear()
        dp, self.dp = self.dp, None
        delete_participant(dp)
