"""Who is on the network: participants, writers and readers read from the DDS built-in
topics (DCPSParticipant, DCPSPublication, DCPSSubscription), with each endpoint's topic,
registered type name, partitions and the QoS it announced. Endpoints of our own
participant are left out. `poll()` takes what arrived; `wait_until(pred)` polls."""
from __future__ import annotations

import time
from dataclasses import dataclass, field


@dataclass(frozen=True)
class QosSummary:
    """The announced policies that RAPID's profiles set, by name as Cyclone spells them
    (None when the remote side did not announce it: other vendors may omit history)."""
    reliability: str | None = None  # Reliable | BestEffort
    durability: str | None = None  # Volatile | TransientLocal | Transient | Persistent
    history: str | None = None  # KeepLast | KeepAll
    depth: int | None = None
    ownership: str | None = None  # Shared | Exclusive
    partitions: tuple[str, ...] = ()

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
                got["partitions"] = tuple(policy.partitions)
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
    raw_qos: object = field(compare=False, repr=False, default=None)

    @property
    def partitions(self) -> tuple[str, ...]:
        return self.qos.partitions or ("",)  # no partition policy is the default partition ""


@dataclass(frozen=True)
class Participant:
    key: str
    properties: dict = field(compare=False, default_factory=dict)  # __Pid, __ProcessName, ... (Cyclone)


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

    def poll(self) -> None:
        for kind, reader in self._readers:
            for s in reader.take(N=512):
                info = getattr(s, "sample_info", None)
                alive = info is None or "ALIVE" == getattr(getattr(info, "instance_state", None), "name", "ALIVE")
                key = str(s.key)
                if kind == "participant":
                    if key == self.own:
                        continue
                    if alive:
                        props = {p.key: p.value for p in (s.qos or ()) if type(p).__name__ == "Property"}
                        self.participants[key] = Participant(key, props)
                    else:
                        self.participants.pop(key, None)
                    continue
                if str(s.participant_key) == self.own:
                    continue
                if alive:
                    self.endpoints[key] = Endpoint(kind, key, str(s.participant_key), s.topic_name, s.type_name,
                                                   QosSummary.of(s.qos), s.qos)
                else:
                    self.endpoints.pop(key, None)

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
