"""The asset's tables as the Rust runtime's DDS layer reads them (runtime/rust/rapid_dds,
`tables_json::asset_of`): the facts of the Python package's asset_tables.py and the C++
bridge's tables.cpp, from the same loaded asset, in lists where order matters (serde_json's
maps are sorted), as one JSON document the generated bridge embeds.

    name, kind, domain, partition
    subsystems    [{name, type}] in CommandConfig order
    types         [{name, commands: [{name, abortable, suspendable, standard, description,
                   stop_timeout_ms, params: [{name, type, unit, min, max, allowed, default}]}]}]
    access        {default, rules: [{source, allow}]} or null
    publications  [{role, type, topic, qos, rate}]
    telemetry     the descriptor's entries as asset_tables.py has them
"""
from __future__ import annotations

import json
from typing import TYPE_CHECKING

from rapidgen.asset.spec import (CustomTelemetry, ImageTelemetry, JointTelemetry, PositionTelemetry, TextTelemetry,
                                 TypedValue)

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset


def _plain(v: object) -> object:
    return list(v) if isinstance(v, tuple) else v


def _typed(v: TypedValue) -> dict:
    d = {"name": v.name, "type": v.type, "unit": v.unit, "min": v.min, "max": v.max, "allowed": list(v.allowed)}
    return {**d, "default": _plain(v.default)} if v.has_default else d


def _telemetry(loaded: "LoadedAsset") -> list[dict]:
    out = []
    for t, topics in zip(loaded.spec.telemetry, loaded.telemetry_topics):
        entry: dict[str, object] = {"kind": t.kind, "topics": topics, "rate": t.rate, "subsystem": t.subsystem,
                                    "values": [{**_typed(v), "has_default": v.has_default}
                                               for v in getattr(t, "values", ())]}
        if isinstance(t, PositionTelemetry):
            entry.update(frame=t.frame, pose_encoding=t.pose_encoding, velocity_encoding=t.velocity_encoding)
        elif isinstance(t, JointTelemetry):
            entry.update(group=t.group, fields=list(t.fields),
                         joints=[{"frame": j.frame, "dof": j.dof, "unit": j.unit, "min": j.min, "max": j.max}
                                 for j in t.joints])
        elif isinstance(t, ImageTelemetry):
            entry.update(sensor=t.sensor, sensor_type=t.sensor_type, mime=t.mime, width=t.width, height=t.height)
        elif isinstance(t, TextTelemetry):
            entry.update(categories=list(t.categories))
        elif isinstance(t, CustomTelemetry):
            entry.update(types={m.role: m.type for m in t.messages})
        out.append(entry)
    return out


def data(loaded: "LoadedAsset") -> dict:
    spec = loaded.spec
    types = [{"name": t.name, "commands": [
        {"name": c.name, "abortable": c.abortable, "suspendable": c.suspendable, "standard": t.standard,
         "description": c.description, "stop_timeout_ms": c.stop_timeout_ms or 0,
         "params": [{**_typed(p), "unit": p.unit or ""} for p in c.parameters]}
        for c in t.commands]} for t in loaded.used_types]
    acc = spec.access_control
    access = None if acc is None else {"default": acc.default,
                                       "rules": [{"source": r.source, "allow": list(r.allow)} for r in acc.rules]}
    return {"name": spec.name, "kind": spec.kind, "domain": spec.domain, "partition": spec.partition,
            "subsystems": [{"name": s.name, "type": s.type} for s in loaded.subsystems], "types": types,
            "access": access,
            "publications": [{"role": p.role, "type": p.type, "topic": p.topic, "qos": p.qos, "rate": p.rate}
                             for p in loaded.publications],
            "telemetry": _telemetry(loaded)}


def json_text(loaded: "LoadedAsset") -> str:
    """One JSON document on one line, stable run to run (insertion order); a
    non-finite number is refused (JSON has none; an unbounded limit is null already)."""
    return json.dumps(data(loaded), separators=(",", ":"), ensure_ascii=False, allow_nan=False)
