"""Who is on the network: participants, writers and readers read from the DDS built-in
topics (DCPSParticipant, DCPSPublication, DCPSSubscription), with each endpoint's topic,
registered type name, partitions and the QoS it announced. Endpoints of our own
participant are left out. `poll()` takes what arrived; `wait_until(pred)` polls.

Discovery data comes from any participant on the domain, so it is untrusted and bounded:
- A built-in sample cyclonedds cannot turn into Python (invalid UTF-8 in a name, a QoS it
  cannot convert) is dropped alone: samples are taken one at a time, so one bad sample
  never loses the others; `dropped` counts them per built-in topic with the first error.
- At most MAX_PARTICIPANTS participants and MAX_ENDPOINTS endpoints are kept, at most
  MAX_ENDPOINT_PARTITIONS partition names per endpoint (the first ones announced; names
  longer than MAX_NAME are not kept), MAX_PROPERTIES participant properties of at most
  MAX_NAME characters; topic and type names longer than MAX_NAME are not kept. What was
  left out is counted in `ignored` (for a tool's output).
- A poll takes at most POLL_LIMIT samples per built-in topic; the rest wait for the next.

The samples come through cyclonedds' own built-in readers (their data is not CDR for a
generated type), so rapid_runtime.untrusted.GuardedReader cannot take them; `_take` applies its
rules (dropped alone, counted, small batches) here.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

MAX_PARTICIPANTS = 1024
MAX_ENDPOINTS = 8192
MAX_ENDPOINT_PARTITIONS = 64
MAX_PROPERTIES = 32
MAX_NAME = 256
POLL_LIMIT = 4096


@dataclass(frozen=True)
class QosSummary:
    """The announced policies that RAPID's profiles set, by name as Cyclone spells them
    (None when the remote side did not announce it: other vendors may omit history)."""
    reliability: str | None = None  # Reliable | BestEffort
    durability: str | None = None  # Volatile | TransientLocal | Transient | Persistent
    history: str | None = None  # KeepLast | KeepAll
    depth: int | None = None
    ownership: str | None = None  # Shared | Exclusive
    partitions: tuple[str, ...] = ()  # at most MAX_ENDPOINT_PARTITIONS
    partitions_left_out: int = 0  # announced partitions not kept (over the cap or too long)

    @classmethod
    def of(cls, qos) -> "QosSummary":
        got: dict = {}
        for policy in qos or ():
            family, _, variant = type(policy).__name__.partition(".")
            if family == "Reliability":
                got["reliability"] = variant
            elif family == "Durability":
                got["durability"] = variant
            elif family == "History":
                got["history"], got["depth"] = variant, getattr(policy, "depth", None)
            elif family == "Ownership":
                got["ownership"] = variant
            elif family == "Partition":
                names = list(policy.partitions)
                kept = tuple(p for p in names if len(p) <= MAX_NAME)[:MAX_ENDPOINT_PARTITIONS]
                got["partitions"], got["partitions_left_out"] = kept, len(names) - len(kept)
        return cls(**got)

    def text(self) -> str:
        hist = f"{self.history}({self.depth})" if self.history == "KeepLast" else self.history
        return f"{self.reliability}, {self.durability}, {hist}"


@dataclass(frozen=True)
class Endpoint:
    kind: str  # writer | reader
    key: str
    participant: str
    topic: str
    type_name: str
    qos: QosSummary
    raw_qos: object = field(compare=False, repr=False, default=None)  # None when partitions were left out

    @property
    def partitions(self) -> tuple[str, ...]:
        return self.qos.partitions or ("",)  # no partition policy is the default partition ""


@dataclass(frozen=True)
class Participant:
    key: str
    properties: dict = field(compare=False, default_factory=dict)  # __Pid, __ProcessName, ... (Cyclone)


@dataclass
class BadSample:
    """Built-in samples of one kind that could not be read."""
    count: int = 0
    first_error: str = ""


class Discovery:
    """Built-in topic readers on `participant` (a cyclonedds DomainParticipant)."""

    def __init__(self, participant) -> None:
        from cyclonedds.builtin import (BuiltinDataReader, BuiltinTopicDcpsParticipant,
                                        BuiltinTopicDcpsPublication, BuiltinTopicDcpsSubscription)
        self.own = str(participant.guid)
        self._readers = [("participant", BuiltinDataReader(participant, BuiltinTopicDcpsParticipant)),
                         ("writer", BuiltinDataReader(participant, BuiltinTopicDcpsPublication)),
                         ("reader", BuiltinDataReader(participant, BuiltinTopicDcpsSubscription))]
        self.participants: dict[str, Participant] = {}
        self.endpoints: dict[str, Endpoint] = {}
        self.type_ids: dict[str, object] = {}  # writer GUID -> its XTypes type identifier, when announced
        self.dropped: dict[str, BadSample] = {}  # participant | writer | reader -> samples not read
        self.ignored: dict[str, int] = {}  # what the caps left out: participants, endpoints, partitions, ...

    def _take(self, kind: str, reader) -> list:
        """Up to POLL_LIMIT samples, one at a time: a sample cyclonedds cannot convert
        raises inside take() and is lost, alone."""
        from rapidgen.textsafe import visible
        out: list = []
        failures = 0
        while len(out) + failures < POLL_LIMIT:
            try:
                got = reader.take(N=1)
            except Exception as exc:  # this one sample is gone; the next take goes on
                bad = self.dropped.setdefault(kind, BadSample())
                bad.count += 1
                if bad.count == 1:
                    bad.first_error = visible(f"{type(exc).__name__}: {exc}"[:160])
                failures += 1
                continue
            if not got:
                break
            out.extend(got)
        return out

    def _ignore(self, what: str, n: int = 1) -> None:
        self.ignored[what] = self.ignored.get(what, 0) + n

    def poll(self) -> None:
        from cyclonedds.core import InstanceState

        for kind, reader in self._readers:
            for s in self._take(kind, reader):
                info = getattr(s, "sample_info", None)
                # a participant or endpoint that left comes as a key-only sample (InvalidSample)
                alive = info is None or (bool(info.valid_data) and info.instance_state == InstanceState.Alive)
                key = str(getattr(getattr(s, "key_sample", s), "key", ""))
                if not alive:
                    if kind == "participant":
                        self.participants.pop(key, None)
                    else:
                        self.endpoints.pop(key, None)
                        self.type_ids.pop(key, None)
                    continue
                if kind == "participant":
                    if key != self.own:
                        self._participant(key, s, alive)
                    continue
                if str(s.participant_key) == self.own:
                    continue
                self._endpoint(kind, key, s)

    def _participant(self, key: str, s, alive: bool) -> None:
        if not alive:
            self.participants.pop(key, None)
            return
        if key not in self.participants and len(self.participants) >= MAX_PARTICIPANTS:
            self._ignore("participants")
            return
        props: dict = {}
        for p in s.qos or ():
            if type(p).__name__ == "Property":
                if len(props) >= MAX_PROPERTIES or len(p.key) > MAX_NAME:
                    self._ignore("participant properties")
                    continue
                props[p.key] = p.value[:MAX_NAME]
        self.participants[key] = Participant(key, props)

    def _endpoint(self, kind: str, key: str, s) -> None:
        if not isinstance(s.topic_name, str) or not isinstance(s.type_name, str):
            return  # a sample without data (Cyclone sends one now and then): nothing to learn
        if len(s.topic_name) > MAX_NAME or len(s.type_name) > MAX_NAME:
            self._ignore("endpoints with a name over 256 characters")
            return
        if key not in self.endpoints and len(self.endpoints) >= MAX_ENDPOINTS:
            self._ignore("endpoints")
            return
        qos = QosSummary.of(s.qos)
        if qos.partitions_left_out and key not in self.endpoints:
            self._ignore("partition names of an endpoint", qos.partitions_left_out)
        self.endpoints[key] = Endpoint(kind, key, str(s.participant_key), s.topic_name, s.type_name, qos,
                                       None if qos.partitions_left_out else s.qos)
        tid = getattr(s, "type_id", None)
        if kind == "writer" and tid is not None:
            self.type_ids[key] = tid

    def find(self, kind: str | None = None, topic: str | None = None, partition: str | None = None) -> list[Endpoint]:
        """Endpoints (after a poll), filtered; partition matches exactly or through '*'."""
        self.poll()
        return [e for e in self.endpoints.values()
                if (kind is None or e.kind == kind) and (topic is None or e.topic == topic)
                and (partition is None or partition in e.partitions or "*" in e.partitions)]

    def wait_until(self, predicate, timeout: float, step: float = 0.05) -> bool:
        end = time.monotonic() + timeout
        while True:
            self.poll()
            if predicate(self):
                return True
            if time.monotonic() >= end:
                return False
            time.sleep(step)

    def notes(self) -> list[str]:
        """What was dropped or left out, one line each (for a tool's output)."""
        out = [f"{b.count} discovery sample(s) of {kind}s could not be read and were dropped ({b.first_error})"
               for kind, b in self.dropped.items()]
        caps = {"participants": MAX_PARTICIPANTS, "endpoints": MAX_ENDPOINTS,
                "partition names of an endpoint": MAX_ENDPOINT_PARTITIONS,
                "participant properties": MAX_PROPERTIES}
        out += [f"{n} {what} left out" + (f" (cap {caps[what]})" if what in caps else "")
                for what, n in self.ignored.items()]
        return out
