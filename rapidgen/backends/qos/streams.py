"""Fast DDS profiles of an asset's setpoint streams (LoadedAsset.streams): one
data_writer/data_reader pair per stream, `RapidStream_<name>`.

Why each setting (docs/realtime.md): a setpoint is worth only while it is fresh, so best
effort, volatile, keep last 1 (a late sample is never resent, an old one never queued);
DEADLINE is the stream's period bound, AUTOMATIC LIVELINESS notices a writer that is gone;
writers publish SYNCHRONOUS (no sending thread between write() and the socket); histories
are PREALLOCATED_WITH_REALLOC with every sample allocated up front, so a steady stream
allocates nothing (Fast DDS docs, use_cases/realtime).
"""
from __future__ import annotations

from dataclasses import dataclass

READER_INSTANCES = 4  # writers of one stream a reader keeps apart (hdr is the key)


@dataclass(frozen=True)
class Duration:
    sec: int
    nanosec: int


@dataclass(frozen=True)
class StreamProfile:
    name: str
    stream: str
    description: str
    writer_partition: str
    reader_partition: str
    deadline: Duration
    lease: Duration
    announcement: Duration
    reader_instances: int = READER_INSTANCES


def duration(ms: float) -> Duration:
    ns = round(ms * 1_000_000)
    return Duration(ns // 1_000_000_000, ns % 1_000_000_000)


def profiles(asset) -> list[StreamProfile]:
    if asset is None:
        return []
    own = asset.spec.partition or asset.spec.name
    return [StreamProfile(s.profile, s.name, f"{s.direction} stream {s.name}: {s.type} on {s.topic}, "
                          f"{s.rate:g} Hz, deadline {s.deadline_ms:g} ms, lease {s.liveliness_ms:g} ms",
                          own, s.partition, duration(s.deadline_ms), duration(s.liveliness_ms),
                          duration(s.liveliness_ms / 4))
            for s in asset.streams]
