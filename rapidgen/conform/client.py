"""The runner's own DDS endpoints in the asset's partition, each with its topic's
profile QoS (so an incompatibility the asset causes shows up as a status here):
a command writer, an ack reader, a reader per config and telemetry topic. One thread
takes every sample as it arrives and stamps it with its arrival time.

The wire is untrusted (any participant in the partition may write any topic, with any
bytes), so every take goes through rapid_runtime.untrusted.GuardedReader: a sample that does not
decode is dropped alone and counted against its writer, a durable sample repeated by its
writer is decoded once, batches are small. Samples are attributed before they are decoded:
only those of the asset's own participants (Session.find_asset) are kept and judged; a
stranger's are counted per participant and topic (decoded only when small, to tell
undecodable ones and acks answering the runner's commands) and never judged. What is kept
is bounded per topic and per cmdId; what was not kept is counted for the report."""
from __future__ import annotations

import collections
import itertools
import math
import os
import threading
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from rapid_runtime.untrusted import GuardedReader

if TYPE_CHECKING:
    from cyclonedds.sub import DataReader

COMMAND, ACK = "rapid_command", "rapid_ack"

# Batches per take: a config may be 4.6 MB at its IDL bounds (raw bytes are held per batch).
CONFIG_BATCH, BATCH = 2, 32
TAKE_PER_ROUND = 256  # samples taken from one reader before the pump turns to the next
# What is kept of the asset's samples, per topic: the latest KEEP_SAMPLES, and at most
# KEEP_BYTES of wire bytes among them (a durable sample repeated by its writer counts once).
KEEP_SAMPLES, KEEP_BYTES = 2048, 32 << 20
KEEP_ACKS_PER_CMD = 64  # acks kept per cmdId the runner sent
KEEP_OTHER_ACKS = 1024  # acks kept for cmdIds the runner did not send (CMD-11 and CMD-12 look at them)
# cmdIds seen on rapid_command (any commander's, the runner's too), remembered: an ack whose
# cmdId nobody sent is evidence (CMD-12) only when it is not one of these.
KEEP_COMMANDED = 8192
STRANGER_DECODE = 64 << 10  # a stranger's sample larger than this is counted, not decoded
MAX_STRANGERS = 64  # participants tallied one by one; past this, as "other participants"
MAX_WRITERS = 4096  # writer handle -> participant, remembered
UNKNOWN = "unknown"  # a sample whose writer had left when it was taken


@dataclass
class Received:
    at: float  # time.monotonic() at arrival
    sample: Any
    size: int = 0  # wire bytes decoded for it (0: a repeat of the writer's previous sample)


@dataclass
class AckSeen:
    index: int  # arrival order over all acks
    at: float
    cmd_id: str
    status: str
    completed: str
    message: str
    asset: str
    src: str
    # when the asset's writer wrote it (DDS source timestamp, ns): the order the asset wrote acks
    # in. `index` is the order they were taken in, and one take returns a keyed topic's samples
    # instance by instance, not as they came (the header's stamp may be the command's, unrefreshed)
    stamp: int = 0


@dataclass
class Stranger:
    """What one participant that is not the asset sent us (counted, never judged)."""
    participant: str
    samples: dict[str, list[int]] = field(default_factory=dict)  # topic -> [count, bytes, not decoded]
    acks_for_runner: int = 0  # its acks carrying a cmdId the runner sent


@dataclass
class Kept:
    """The asset's samples of one topic, bounded (KEEP_SAMPLES, KEEP_BYTES)."""
    items: collections.deque = field(default_factory=collections.deque)
    bytes: int = 0
    total: int = 0
    discarded: int = 0
    discarded_bytes: int = 0

    def add(self, r: Received) -> None:
        self.items.append(r)
        self.bytes += r.size
        self.total += 1
        while len(self.items) > KEEP_SAMPLES or (self.bytes > KEEP_BYTES and len(self.items) > 1):
            old = self.items.popleft()
            self.bytes -= old.size
            self.discarded += 1
            self.discarded_bytes += old.size


def enum_name(value) -> str:
    return getattr(value, "name", None) or str(value)


class _Guard(GuardedReader):
    """GuardedReader that attributes each sample to its writer's participant before decoding
    it: a stranger's sample is tallied and never handed out."""

    def __init__(self, reader, client: "Client", topic: str, dedupe: bool, batch: int) -> None:
        super().__init__(reader, dedupe=dedupe, batch=batch)
        self.client, self.topic = client, topic

    def _decode(self, data_type, data: bytes, info):
        who = self.client.participant_of(self.reader, info.publication_handle)
        if who not in self.client.asset_participants:
            small = len(data) <= STRANGER_DECODE
            sample = super()._decode(data_type, data, info) if small else None
            self.client.stranger(who, self.topic, len(data), sample, decoded=small)
            return None
        reused = self.reused
        sample = super()._decode(data_type, data, info)
        if sample is not None:
            sample.wire_size = 0 if self.reused > reused else len(data)
        return sample


class Client:
    def __init__(self, bindings, participant, asset: str) -> None:
        from cyclonedds.core import Listener
        from cyclonedds.pub import DataWriter, Publisher
        from cyclonedds.qos import Policy, Qos
        from cyclonedds.sub import DataReader, Subscriber
        from cyclonedds.topic import Topic

        self.b, self.dp, self.asset = bindings, participant, asset
        self._Policy, self._Qos, self._DataReader, self._Topic = Policy, Qos, DataReader, Topic
        q = bindings.qos
        self.publisher = Publisher(participant, qos=q.publisher())
        self.subscriber = Subscriber(participant, qos=q.subscriber())
        # topic -> {(side, policy id)}: a set, so a stranger's stream of mismatched endpoints stays bounded
        self.incompatible: dict[str, set[tuple[str, int | None]]] = {}
        self._topics: dict[str, object] = {}
        self.lock = threading.Condition()
        self._who_lock = threading.Lock()
        self.readers: dict[str, DataReader[Any]] = {}
        self.guards: dict[str, _Guard] = {}
        self.extra_guards: list[_Guard] = []  # readers a check opens itself (CMD-13): their drops are reported too
        self.listened: dict[str, list] = {}  # topic -> our endpoints with an incompatible-QoS listener
        self.received: dict[str, Kept] = {}
        self.acks: list[AckSeen] = []  # append-only (checks iterate it while the pump appends)
        self._ack_count = 0
        self._acks_per_cmd: collections.Counter[str] = collections.Counter()
        self._other_acks = 0
        self.acks_not_kept = 0
        self.sent: dict[str, Any] = {}  # cmdId -> Command we wrote (the generated type)
        self.sent_at: dict[str, float] = {}  # cmdId -> time.monotonic() when we first wrote it
        # Accounting (CMD-16): who sent each cmdId (the check running, Session.begin), so a command
        # that gets no final ack is named with the check that sent it
        self.sender = ""
        self.origin: dict[str, str] = {}
        # cmdIds any commander wrote (our command reader sees every writer's): bounded, oldest out
        self.commanded: collections.OrderedDict[str, None] = collections.OrderedDict()
        self.command_guard: GuardedReader | None = None
        # participants whose samples are judged (GUIDs as Discovery spells them); set before start()
        self.asset_participants: set[str] = set()
        self.strangers: dict[str, Stranger] = {}
        self._writers: collections.OrderedDict[int, str] = collections.OrderedDict()
        self._ids = itertools.count(1)
        self.command_writer = None
        if COMMAND in q.topics:
            self.command_writer = DataWriter(self.publisher, self.topic(COMMAND, bindings.rapid.Command),
                                             qos=q.writer(COMMAND), listener=self._listener(COMMAND, Listener))
            self.listened.setdefault(COMMAND, []).append(self.command_writer)
        self.stopping = threading.Event()
        self._thread = threading.Thread(target=self._pump, daemon=True, name="conform-readers")

    # ---- endpoints -----------------------------------------------------------------------
    def topic(self, name: str, cls):
        if name not in self._topics:
            self._topics[name] = self._Topic(self.dp, name, cls)
        return self._topics[name]

    def _listener(self, topic: str, Listener):
        def requested(_reader, status):
            self._incompatible(topic, "requested", status)

        def offered(_writer, status):
            self._incompatible(topic, "offered", status)
        return Listener(on_requested_incompatible_qos=requested, on_offered_incompatible_qos=offered)

    def _incompatible(self, topic: str, side: str, status) -> None:
        with self.lock:
            self.incompatible.setdefault(topic, set()).add((side, getattr(status, "last_policy_id", None)))

    def profile_reader(self, topic: str, type_name: str, relaxed: bool = False):
        """A reader of topic with its profile's QoS and KEEP_ALL history (history is local:
        every sample is kept until taken). relaxed: VOLATILE, so it matches a writer whatever
        its durability (the ack reader: a broken ack durability must not hide every ack)."""
        from cyclonedds.core import Listener
        P, Q = self._Policy, self._Qos
        qos = self.b.qos.reader(topic) + Q(P.History.KeepAll)
        if relaxed:
            qos = qos + Q(P.Durability.Volatile)
        listener = None if relaxed else self._listener(topic, Listener)
        reader = self._DataReader(self.subscriber, self.topic(topic, self.b.type_class(type_name)), qos=qos,
                                  listener=listener)
        if listener is not None:
            self.listened.setdefault(topic, []).append(reader)
        return reader

    def guard(self, reader, topic: str) -> _Guard:
        """reader's samples through a GuardedReader that keeps only the asset's (durable
        topics deduplicated, configs in batches of CONFIG_BATCH)."""
        config = topic in self.b.tables["CONFIGS"]
        durable = any(p["topic"] == topic and p["role"] in ("config", "state") for p in self.b.tables["PUBLICATIONS"])
        return _Guard(reader, self, topic, dedupe=config or durable, batch=CONFIG_BATCH if config else BATCH)

    def start(self, topics: dict[str, str]) -> "Client":
        """Read every topic (name -> type) and the acks; start taking samples."""
        for topic, type_name in topics.items():
            if topic != ACK:
                self.readers[topic] = self.profile_reader(topic, type_name)
                self.guards[topic] = self.guard(self.readers[topic], topic)
                self.received[topic] = Kept()
        if self.command_writer is not None:
            self.ack_reader = self.profile_reader(ACK, "rapid::Ack", relaxed=True)
            self.ack_guard: _Guard | None = _Guard(self.ack_reader, self, ACK, dedupe=False, batch=BATCH)
            # Every commander's commands (cmdIds only): an ack for a cmdId nobody sent is a finding
            # (CMD-12), one for another commander's is not. Not listened to: no check judges it.
            keep_all = self._Qos(self._Policy.History.KeepAll)
            self.command_reader = self._DataReader(self.subscriber, self.topic(COMMAND, self.b.rapid.Command),
                                                   qos=self.b.qos.reader(COMMAND) + keep_all)
            self.command_guard = GuardedReader(self.command_reader, batch=BATCH)
        else:
            self.ack_reader = None
            self.ack_guard = None
        self._thread.start()
        return self

    # ---- who wrote it ----------------------------------------------------------------------
    def participant_of(self, reader, handle: int) -> str:
        """The GUID of the participant whose writer has this publication handle (UNKNOWN
        once the writer left)."""
        with self._who_lock:
            got = self._writers.get(handle)
            if got is not None:
                self._writers.move_to_end(handle)
                return got
        try:
            ep = reader.get_matched_publication_data(handle)
        except Exception:  # the writer left already
            ep = None
        if ep is None:
            return UNKNOWN
        got = str(ep.participant_key)
        with self._who_lock:
            self._writers[handle] = got
            while len(self._writers) > MAX_WRITERS:
                self._writers.popitem(last=False)
        return got

    def stranger(self, who: str, topic: str, size: int, sample, decoded: bool) -> None:
        with self.lock:
            s = self.strangers.get(who)
            if s is None:
                key = who if len(self.strangers) < MAX_STRANGERS else "other participants"
                s = self.strangers.setdefault(key, Stranger(key))
            if topic not in s.samples and len(s.samples) >= 64:
                topic = "other topics"
            tally = s.samples.setdefault(topic, [0, 0, 0])
            tally[0] += 1
            tally[1] += size
            tally[2] += not decoded
            if sample is not None and topic == ACK and getattr(sample, "cmdId", None) in self.sent:
                s.acks_for_runner += 1

    # ---- the pump ----------------------------------------------------------------------------
    def _pump(self) -> None:
        while not self.stopping.is_set():
            got = False
            for topic, g in list(self.guards.items()):
                now = time.monotonic()
                samples = g.take_all(TAKE_PER_ROUND)
                if samples:
                    got = True
                    with self.lock:
                        kept = self.received[topic]
                        for s in samples:
                            kept.add(Received(now, s, getattr(s, "wire_size", 0)))
            if self.command_guard is not None:  # before the acks: a command is seen before its answer
                for c in self.command_guard.take_all(TAKE_PER_ROUND):
                    self._commanded(c.cmdId)
            if self.ack_guard is not None:
                now = time.monotonic()
                for s in self.ack_guard.take_all(TAKE_PER_ROUND):
                    with self.lock:
                        self._ack(s, now)
                    got = True
            if got:
                with self.lock:
                    self.lock.notify_all()
            time.sleep(0.005)

    def _commanded(self, cmd_id) -> None:
        if not isinstance(cmd_id, str):
            return
        with self.lock:
            self.commanded[cmd_id] = None
            self.commanded.move_to_end(cmd_id)
            while len(self.commanded) > KEEP_COMMANDED:
                self.commanded.popitem(last=False)

    def _ack(self, s, now: float) -> None:
        """Keep an ack of the asset (caller holds the lock), within the caps."""
        cid = s.cmdId
        self._ack_count += 1
        if cid in self.sent:
            self._acks_per_cmd[cid] += 1
            keep = self._acks_per_cmd[cid] <= KEEP_ACKS_PER_CMD
        else:
            self._other_acks += 1
            keep = self._other_acks <= KEEP_OTHER_ACKS
        if not keep:
            self.acks_not_kept += 1
            return
        self.acks.append(AckSeen(self._ack_count - 1, now, cid, enum_name(s.status), enum_name(s.completedStatus),
                                 s.message, s.hdr.assetName, s.hdr.srcName,
                                 getattr(getattr(s, "sample_info", None), "source_timestamp", 0) or 0))

    def stop(self) -> None:
        self.stopping.set()
        if self._thread.ident is not None:  # (started: find_asset starts it, found or not)
            self._thread.join(timeout=5)

    # ---- what was not judged -------------------------------------------------------------------
    def dropped(self) -> list[str]:
        """One line per writer whose samples did not decode, per topic whose samples were not
        all kept, and for acks not kept."""
        lines = [line for g in [*self.guards.values(), *([self.ack_guard] if self.ack_guard else [])]
                 for line in g.summary()]
        if self.command_guard is not None:
            lines += [f"{line} (commands: their cmdIds tell other commanders' acks from acks for cmdIds nobody sent)"
                      for line in self.command_guard.summary()]
        lines += [f"{line} (a reader a check opened)" for g in self.extra_guards for line in g.summary()]
        with self.lock:
            for topic, k in self.received.items():
                if k.discarded:
                    lines.append(f"{topic}: {k.discarded} older sample(s) of the asset ({_size(k.discarded_bytes)}) "
                                 f"not kept (kept the latest {len(k.items)} of {k.total}: at most {KEEP_SAMPLES} "
                                 f"samples and {_size(KEEP_BYTES)} per topic)")
            if self.acks_not_kept:
                lines.append(f"{ACK}: {self.acks_not_kept} ack(s) of the asset not kept (at most {KEEP_ACKS_PER_CMD} "
                             f"per cmdId sent, {KEEP_OTHER_ACKS} for other cmdIds)")
        return lines

    # ---- commands ------------------------------------------------------------------------
    def new_id(self, source: str) -> str:
        return f"{next(self._ids)}-{source}-{os.getpid()}-{time.time_ns() // 1_000_000}"

    def union(self, dtype: str, value):
        r = self.b.rapid
        if dtype in ("RAPID_FLOAT", "RAPID_DOUBLE"):
            value = float(value)
        elif dtype in ("RAPID_VEC3d", "RAPID_MAT33f"):
            value = [float(x) for x in value]
        return r.ParameterUnion(discriminator=r.DataType[dtype], value=value)

    def send(self, subsystem: str, name: str, args=(), source: str = "", action: str = "QUEUE_BYPASS",
             target: str = "", cmd_id: str | None = None, asset: str | None = None, serial: int = 0) -> str:
        r = self.b.rapid
        cmd_id = self.new_id(source) if cmd_id is None else cmd_id
        hdr = r.Header(srcName=source, assetName=self.asset if asset is None else asset,
                       timeStamp=time.time_ns() // 1000, statusCode=0, serial=serial)
        cmd = r.Command(hdr=hdr, cmdName=name, cmdId=cmd_id, cmdSrc=source, subsysName=subsystem,
                        arguments=[self.union(t, v) for t, v in args], cmdAction=r.QueueAction[action],
                        targetCmdId=target)
        with self.lock:
            self.sent.setdefault(cmd_id, cmd)
            self.sent_at.setdefault(cmd_id, time.monotonic())
            self.origin.setdefault(cmd_id, self.sender)
        if self.command_writer is None:  # callers check Session.needs_commands() first
            raise RuntimeError("the asset takes no commands: no command writer")
        self.command_writer.write(cmd)
        return cmd_id

    def acks_of(self, cmd_id: str) -> list[AckSeen]:
        with self.lock:
            return [a for a in self.acks if a.cmd_id == cmd_id]

    def unsent(self, since: float = 0.0) -> list[AckSeen]:
        """The asset's acks (arrived at or after `since`) whose cmdId nobody sent: neither the
        runner nor any commander seen on rapid_command."""
        with self.lock:
            return [a for a in self.acks if a.at >= since and a.cmd_id not in self.sent
                    and a.cmd_id not in self.commanded]

    def samples(self, topic: str) -> list[Received]:
        with self.lock:
            k = self.received.get(topic)
            return list(k.items) if k else []

    def wait_sample(self, topic: str, timeout: float) -> list[Received]:
        end = time.monotonic() + timeout
        with self.lock:
            while not self.samples(topic) and time.monotonic() < end:
                self.lock.wait(max(0.0, end - time.monotonic()))
            return self.samples(topic)

    # ---- matching ---------------------------------------------------------------------------
    def matched_keys(self, topic: str) -> set[str]:
        """Keys of the remote endpoints our listened endpoints on topic are matched with."""
        out: set[str] = set()
        for ent in self.listened.get(topic, ()):
            reader = hasattr(ent, "get_matched_publications")
            try:
                handles = ent.get_matched_publications() if reader else ent.get_matched_subscriptions()
            except Exception:  # deleted meanwhile
                continue
            for h in handles:
                try:
                    data = ent.get_matched_publication_data(h) if reader else ent.get_matched_subscription_data(h)
                except Exception:  # left meanwhile
                    continue
                if data is not None:
                    out.add(str(data.key))
        return out

    def matched_asset(self, entity, reader: bool) -> bool:
        """entity (our writer or reader) is matched with an endpoint of the asset's."""
        try:
            handles = entity.get_matched_publications() if reader else entity.get_matched_subscriptions()
        except Exception:
            return False
        for h in handles:
            try:
                data = entity.get_matched_publication_data(h) if reader else entity.get_matched_subscription_data(h)
            except Exception:
                continue
            if data is not None and str(data.participant_key) in self.asset_participants:
                return True
        return False


def _size(n: int) -> str:
    return f"{n / (1 << 20):.1f} MiB" if n >= 1 << 20 else f"{n / 1024:.1f} KiB" if n >= 1024 else f"{n} B"


def finite(x) -> bool:
    return isinstance(x, (int, float)) and math.isfinite(x)
