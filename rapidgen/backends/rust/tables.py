"""The asset's tables as the Rust runtime's DDS layer reads them (runtime/rust/rapid_dds,
`asset_json`): the same facts as the Python package's asset_tables.py (they come from
rapidgen.backends.python.asset_tables.tables, one source), in lists where order matters
(serde_json's maps are sorted), as one JSON document the generated bridge embeds.

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

from rapidgen.backends.python.asset_tables import tables

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset


def data(loaded: "LoadedAsset") -> dict:
    t = tables(loaded)
    asset = t["ASSET"]
    types = []
    for type_name, commands in t["COMMANDS"].items():
        types.append({"name": type_name, "commands": [
            {"name": name, "abortable": c["abortable"], "suspendable": c["suspendable"], "standard": c["standard"],
             "description": c["description"], "stop_timeout_ms": c.get("stop_timeout_ms") or 0,
             "params": [{"name": p["name"], "type": p["type"], "unit": p["unit"] or "", "min": p["min"],
                         "max": p["max"], "allowed": p["allowed"],
                         **({"default": p["default"]} if p["has_default"] else {})}
                        for p in c["parameters"]]}
            for name, c in commands.items()]})
    return {"name": asset["name"], "kind": asset["kind"], "domain": asset["domain"], "partition": asset["partition"],
            "subsystems": [{"name": n, "type": ty} for n, ty in t["SUBSYSTEMS"].items()], "types": types,
            "access": t["ACCESS"], "publications": t["PUBLICATIONS"], "telemetry": t["TELEMETRY"]}


def json_text(loaded: "LoadedAsset") -> str:
    """One JSON document on one line, stable run to run (insertion order); a
    non-finite number is refused (JSON has none; an unbounded limit is null already)."""
    return json.dumps(data(loaded), separators=(",", ":"), ensure_ascii=False, allow_nan=False)
