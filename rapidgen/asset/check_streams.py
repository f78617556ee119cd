"""Setpoint stream checks: types, timing, topics, and the agent value keys a stream reports in."""
from __future__ import annotations

from typing import TYPE_CHECKING

from rapidgen.asset.spec import AgentTelemetry
from rapidgen.diagnostics import did_you_mean

if TYPE_CHECKING:
    from rapidgen.asset.check import Checker
    from rapidgen.asset.streams import Stream

_INPUT_ONLY = ("source", "on_loss", "state_key", "missed_key")


def check_streams(c: "Checker") -> None:
    streams = c.loaded.streams
    if not streams:
        return
    c.duplicates([s.spec for s in streams], lambda s: s.name, "stream")
    subs = [s.name for s in c.loaded.subsystems]
    taken = {p.topic: p for p in c.loaded.publications}
    seen: dict[tuple[str, str], "Stream"] = {}
    for s in streams:
        sp = s.spec
        _type(c, s)
        if s.deadline_ms < s.period_ms:
            c.sink.error("RG1314", f"stream '{s.name}': deadline {s.deadline_ms:g} ms is shorter than its period "
                         f"{s.period_ms:g} ms ({s.rate:g} Hz)",
                         sp.at("deadline_ms") if sp.has("deadline_ms") else sp.at("rate"),
                         f"every sample would miss it; give at least {s.period_ms:g} ms (three periods is usual)")
        elif s.liveliness_ms < s.deadline_ms:
            c.sink.error("RG1314", f"stream '{s.name}': liveliness lease {s.liveliness_ms:g} ms is shorter than its "
                         f"deadline {s.deadline_ms:g} ms", sp.at("liveliness_ms"),
                         "a writer is declared lost before a sample is even late; lengthen the lease")
        if s.topic in taken:
            p = taken[s.topic]
            where = f"the telemetry entry at line {p.loc.line}" if p.source is not None else "the asset's subsystems"
            c.sink.error("RG1315", f"stream topic '{s.topic}' is also published by {where}",
                         sp.at("topic") if sp.has("topic") else sp.at("name"),
                         "give the stream a topic of its own ('topic:' or another name)")
        key = (s.partition, s.topic)
        if key in seen and seen[key].name != s.name:
            c.sink.error("RG1315", f"stream topic '{s.topic}' is also the topic of stream '{seen[key].name}'",
                         sp.at("topic") if sp.has("topic") else sp.at("name"),
                         f"first used at line {seen[key].loc.line}; give each stream its own topic")
        seen.setdefault(key, s)
        if sp.subsystem is not None and sp.subsystem not in subs:
            c.sink.error("RG1103", f"unknown subsystem '{sp.subsystem}'", sp.at("subsystem"),
                         did_you_mean(sp.subsystem, subs) or f"subsystems: {', '.join(subs) or 'none'}")
        if sp.source is not None:
            c.bound(sp.source, sp.at("source"), "stream source", "rapid::Header", "assetName")
        c.bound(s.topic, sp.at("topic") if sp.has("topic") else sp.at("name"), "stream topic",
                "rapid::AgentConfig", "topics")
        if s.direction == "output":
            for field in _INPUT_ONLY:
                if sp.has(field):
                    c.sink.warning("RG1317", f"'{field}' means nothing on an output stream", sp.at(field),
                                   "remove it, or make the stream 'direction: input'")
            continue
        _key(c, s, "state_key", sp.state_key, ("RAPID_STRING",))
        _key(c, s, "missed_key", sp.missed_key, ("RAPID_INT", "RAPID_LONGLONG"))


def _type(c: "Checker", s: "Stream") -> None:
    if c.facts.model is None:
        return
    loc = s.spec.at("type")
    if c.facts.struct(s.type) is None:
        names = c.facts.struct_names()
        c.sink.error("RG1313", f"stream '{s.name}': unknown type '{s.spec.type}'", loc,
                     did_you_mean(s.type, names) or "a RAPID message such as JointSample or PositionSample")
    elif not c.facts.is_message(s.type):
        c.sink.error("RG1313", f"stream '{s.name}': '{s.type}' is not a RAPID message (no rapid::Message base)",
                     loc, "setpoints are RAPID messages with a header: JointSample, PositionSample, ...")


def _key(c: "Checker", s: "Stream", field: str, key: str | None, types: tuple[str, ...]) -> None:
    if key is None:
        return
    agents = [t for t in c.spec.telemetry if isinstance(t, AgentTelemetry)]
    values = {v.name: v for t in agents[:1] for v in t.values}  # the runtime reports in the first agent entry
    loc = s.spec.at(field)
    if not agents:
        c.sink.error("RG1316", f"stream '{s.name}': '{field}: {key}' needs agent telemetry", loc,
                     f"add '- {{kind: agent, values: [{{key: {key}, type: {types[0]}}}]}}' under telemetry")
    elif key not in values:
        c.sink.error("RG1316", f"stream '{s.name}': '{key}' is not a value key of the agent telemetry", loc,
                     did_you_mean(key, values) or f"add '{{key: {key}, type: {types[0]}}}' to its values")
    elif values[key].type not in types:
        c.sink.error("RG1316", f"stream '{s.name}': value key '{key}' is {values[key].type}; "
                     f"{field} needs {' or '.join(types)}", loc,
                     f"declare it 'type: {types[0]}' (line {values[key].loc.line})")
