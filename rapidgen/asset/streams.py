"""Setpoint streams: each descriptor `streams:` entry with its defaults resolved
(resolved.LoadedAsset.streams is the one caller).

A stream is not a publication: it has no config, is not listed in AgentConfig.topics, and
the Python runtime does not serve it (docs/asset-descriptor.md "Setpoint streams").
"""
from __future__ import annotations

from dataclasses import dataclass

from rapidgen.asset.facts import Facts
from rapidgen.asset.spec import AssetSpec, StreamSpec
from rapidgen.asset.topics import STANDARD_MESSAGES, topic_constant
from rapidgen.diagnostics import SourceLoc

PROFILE_PREFIX = "RapidStream_"
MIN_LEASE_MS = 100.0  # AUTOMATIC liveliness below this costs an announcement every few ms
_CONSTS = {type_: const for msgs in STANDARD_MESSAGES.values() for _role, type_, const in msgs}


@dataclass(frozen=True)
class Stream:
    name: str
    direction: str  # input | output
    type: str  # scoped IDL name
    topic: str
    partition: str  # the writer's: the source asset's partition (inputs), this asset's (outputs)
    rate: float  # Hz
    deadline_ms: float
    liveliness_ms: float
    on_loss: str  # stop | hold | none (outputs: none)
    subsystem: str | None
    state_key: str | None
    missed_key: str | None
    profile: str  # the QoS profile of the generated library: RapidStream_<name>
    description: str
    loc: SourceLoc
    spec: StreamSpec

    @property
    def period_ms(self) -> float:
        return 1000.0 / self.rate


def scoped(type_: str) -> str:
    return type_ if "::" in type_ else "rapid::" + type_


def resolve(spec: AssetSpec, facts: Facts) -> list[Stream]:
    out = []
    for s in spec.streams:
        type_ = scoped(s.type)
        const = _CONSTS.get(type_)
        base = topic_constant(facts, const) if const else "rapid_stream"
        deadline = float(s.deadline_ms) if s.deadline_ms is not None else 3000.0 / s.rate
        lease = float(s.liveliness_ms) if s.liveliness_ms is not None else max(MIN_LEASE_MS, 4 * deadline)
        own = spec.partition or spec.name
        out.append(Stream(
            name=s.name, direction=s.direction, type=type_, topic=s.topic or f"{base}-{s.name}",
            partition=(s.source or own) if s.direction == "input" else own, rate=float(s.rate),
            deadline_ms=deadline, liveliness_ms=lease, on_loss=s.on_loss if s.direction == "input" else "none",
            subsystem=s.subsystem, state_key=s.state_key, missed_key=s.missed_key,
            profile=PROFILE_PREFIX + s.name, description=s.description, loc=s.loc, spec=s))
    return out
