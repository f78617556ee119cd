"""What the spy saw, as plain data: participants, and per partition (asset) its topics
with writers, readers, role, recognised QoS profile, measured rate and latest sample.
Built from a Watcher's state; no DDS here, so it is tested without a network."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from rapid_runtime.plain import plain  # one JSON form of a sample for every tool (the runtime's)

from rapidgen.qos.spec import QosSpec, default_library

ROLE_BY_SUFFIX = (("Config", "config"), ("State", "state"), ("Sample", "sample"), ("Command", "command"),
                  ("Ack", "ack"))
# Cyclone's spelling of the announced policies -> the QoS library's
_RELIABILITY = {"Reliable": "reliable", "BestEffort": "best_effort"}
_DURABILITY = {"Volatile": "volatile", "TransientLocal": "transient_local", "Transient": "transient",
               "Persistent": "persistent"}
_HISTORY = {"KeepLast": "keep_last", "KeepAll": "keep_all"}


def role_of(type_name: str, declared: str | None = None) -> str:
    """config/state/sample/command/ack from the descriptor when it says, else the type's
    name (RAPID's naming: *Config, *State, *Sample, Command, Ack); TextMessage etc.: other."""
    if declared:
        return declared
    last = type_name.replace(".", "::").rsplit("::", 1)[-1]
    return next((role for suffix, role in ROLE_BY_SUFFIX if last.endswith(suffix)), "other")


def profile_of(qos, type_name: str, writer: bool, library: QosSpec | None = None,
               declared: str | None = None) -> tuple[str | None, str | None]:
    """(the library profile whose effective policies the announced QoS has, the profile
    the library assigns to the type). Reliability, durability and history kind are
    compared; depth is the endpoint's own (runtime ack writers keep 8) and is not.
    The expected profile (the descriptor's, else the library's rule for the type) wins
    among equals (Config, State and ReliableDurable agree)."""
    lib = library or default_library()
    expected = declared if declared and lib.has_profile(declared) else lib.profile_for_type(type_name.replace(".", "::"))
    seen = (_RELIABILITY.get(qos.reliability or ""), _DURABILITY.get(qos.durability or ""),
            _HISTORY.get(qos.history or "") if qos.history else None)
    names = [expected] if expected else []
    names += [p.name for p in lib.profiles if p.name != expected and p.name != lib.default_profile.name]
    for name in names:
        pol = lib.effective(name)[0 if writer else 1]
        want = (pol.reliability, pol.durability, pol.history.kind if pol.history else None)
        if want[:2] == seen[:2] and (seen[2] is None or want[2] == seen[2]):
            return name, expected
    return None, expected


@dataclass
class EndpointView:
    kind: str  # writer | reader
    key: str
    participant: str
    type_name: str
    qos: str  # "Reliable, TransientLocal, KeepLast(1)"
    profile: str | None  # recognised RAPID profile, None when none matches
    rate: float | None = None  # writers: Hz measured over the window (3 samples or more)


@dataclass
class TopicView:
    partition: str
    topic: str
    type_name: str
    role: str
    writers: list[EndpointView] = field(default_factory=list)
    readers: list[EndpointView] = field(default_factory=list)
    expected_profile: str | None = None
    samples: int = 0
    rate: float | None = None  # Hz: the median of its writers' measured rates
    declared_rate: float | None = None
    latest: dict | None = None  # the latest sample, plain (configs: for the dictionary view)
    decodable: bool = True  # a type we have bindings for

    @property
    def profile(self) -> str | None:
        profs = {e.profile for e in self.writers} or {e.profile for e in self.readers}
        return next(iter(profs)) if len(profs) == 1 else ("mixed" if profs else None)


@dataclass
class AssetView:
    partition: str
    name: str  # the configs' hdr.assetName, else the partition
    participants: list[str] = field(default_factory=list)
    topics: list[TopicView] = field(default_factory=list)

    def topic(self, name: str) -> TopicView | None:
        return next((t for t in self.topics if t.topic == name), None)


@dataclass
class Snapshot:
    domain: int
    seconds: float
    participants: list[dict] = field(default_factory=list)  # key, process, pid, host
    assets: list[AssetView] = field(default_factory=list)
    findings: list = field(default_factory=list)  # diagnose.Finding
    dropped: list[dict] = field(default_factory=list)  # undecodable samples per writer (Watcher.dropped)
    limits: list[str] = field(default_factory=list)  # what a cap left out (Watcher.limits)

    def asset(self, name_or_partition: str) -> AssetView | None:
        return next((a for a in self.assets if name_or_partition in (a.name, a.partition)), None)

    def as_dict(self) -> dict:
        return {"domain": self.domain, "seconds": round(self.seconds, 3), "participants": self.participants,
                "assets": [dict(dataclasses.asdict(a), topics=[dict(dataclasses.asdict(t), profile=t.profile)
                                                               for t in a.topics]) for a in self.assets],
                "findings": [f.as_dict() for f in self.findings], "dropped": self.dropped, "limits": self.limits}


def rate(arrivals: list[float]) -> float | None:
    """Samples per second from one writer's send (or arrival) times: (n - 1) gaps over
    their span; None under 3 samples (a durable writer's one sample is not a rate)."""
    if len(arrivals) < 3 or arrivals[-1] <= arrivals[0]:
        return None
    return (len(arrivals) - 1) / (arrivals[-1] - arrivals[0])


def pair_config(topic: str, configs: set[str], declared: dict[str, str] | None = None) -> str | None:
    """The config topic a sample/state topic pairs with: the descriptor's pairing, else
    RAPID's naming (rapid_joint_sample-arm -> rapid_joint_config-arm)."""
    if declared and topic in declared:
        return declared[topic]
    for suffix in ("_sample", "_state"):
        if suffix in topic:
            cand = topic.replace(suffix, "_config", 1)
            if cand in configs:
                return cand
    return None
