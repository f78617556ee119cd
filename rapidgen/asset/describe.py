"""`rapidgen validate` and `rapidgen describe`: the descriptor as an operator reads it.

describe prints plain aligned tables (no colour, no terminal width guessing) so the
output can be diffed, pasted into a report, or grepped. Descriptor text is shown with
what is not printable escaped (\x1b, not an escape sequence the terminal would obey).
"""
from __future__ import annotations

import sys
from typing import Callable

from rapidgen.asset.load import LoadedAsset, load_asset
from rapidgen.asset.spec import (AgentTelemetry, ImageTelemetry, JointTelemetry, PositionTelemetry,
                                 Threshold, TypedValue)
from rapidgen.textsafe import visible
from rapidgen.diagnostics import DiagnosticSink

Report = Callable[[DiagnosticSink], None]


def run_validate(files: list[str], rapid_dir: str | None, sink: DiagnosticSink, report: Report) -> int:
    ok_lines = []
    for path in files:
        before = len(sink.errors)
        loaded = load_asset(path, sink, rapid_dir)
        if loaded is not None and len(sink.errors) == before:
            ok_lines.append(visible(f"{path}: valid ({_summary(loaded)})"))
    report(sink)
    for line in ok_lines:
        print(line)
    return 1 if sink.has_errors else 0


def run_describe(path: str, rapid_dir: str | None, sink: DiagnosticSink, report: Report,
                 as_json: bool = False) -> int:
    loaded = load_asset(path, sink, rapid_dir)
    report(sink)
    if loaded is None or sink.has_errors:
        return 1
    if as_json:
        import json
        sys.stdout.write(json.dumps(describe_data(loaded), indent=2, ensure_ascii=True) + "\n")
    else:
        sys.stdout.write(describe(loaded))
    return 0


def _summary(loaded: LoadedAsset) -> str:
    spec = loaded.spec
    cmds = sum(len(t.commands) for t in loaded.used_types)
    topics = len(loaded.publications)
    n_subs = len(loaded.subsystems)
    return (f"asset {spec.name}: {n_subs} subsystem{'s' * (n_subs != 1)}, {cmds} command{'s' * (cmds != 1)}, "
            f"{topics} topic{'s' * (topics != 1)}")


# -- formatting ----------------------------------------------------------------------------
def _n(x) -> str:
    return "-" if x is None else (str(x) if isinstance(x, int) else f"{x:g}")


def table(headers: list[str], rows: list[list[str]], indent: int = 2) -> list[str]:
    rows = [[visible(c) for c in r] for r in rows]  # escaped before measuring, so columns align
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(headers)]
    fmt = lambda cells: (" " * indent + "  ".join(c.ljust(w) for c, w in zip(cells, widths))).rstrip()  # noqa: E731
    return [fmt(headers), fmt(["-" * w for w in widths])] + [fmt(r) for r in rows]


def _range(v) -> str:
    if v.min is None and v.max is None:
        return "-"
    return f"[{_n(v.min) if v.min is not None else '-inf'}, {_n(v.max) if v.max is not None else 'inf'}]"


def _default(v: TypedValue) -> str:
    if not v.has_default:
        return "-"
    d = v.default
    if isinstance(d, bool):
        return "true" if d else "false"
    if isinstance(d, list):
        return "[" + ", ".join(_n(x) for x in d) + "]"
    return repr(d) if isinstance(d, str) else _n(d)


def _rate(p) -> str:
    if p.rate:
        return f"{_n(p.rate)} Hz"
    return "per command" if p.role == "ack" else "on change"


def _threshold(t: Threshold | None) -> str:
    if t is None:
        return "-"
    parts = ([f"< {_n(t.below)}"] if t.below is not None else []) + ([f"> {_n(t.above)}"] if t.above is not None else [])
    return " or ".join(parts)


def describe(loaded: LoadedAsset) -> str:
    spec = loaded.spec
    out = [f"{spec.name} ({spec.kind})"]
    if spec.description:
        out.append(f"  {spec.description.strip()}")
    out.append(f"  DDS domain {spec.domain}, partition '{spec.partition}'"
               + (f"; tags: {', '.join(spec.tags)}" if spec.tags else ""))
    subs = loaded.subsystems
    types = loaded.used_types
    out += ["", "Subsystems"]
    if subs:
        by_type = {t.name: t for t in types}
        out += table(["subsystem", "type", "commands", "description"],
                     [[s.name, s.type, str(len(by_type[s.type].commands)) if s.type in by_type else "?",
                       s.description] for s in subs])
    else:
        out.append("  none: the asset takes no commands (telemetry only)")
    if types:
        out += ["", "Command dictionary"]
        for t in types:
            users = [s.name for s in subs if s.type == t.name]
            out.append(f"  {t.name}{' (standard)' if t.standard else ''}: {', '.join(users)}")
            if not t.commands:
                out.append("    no commands")
            for c in t.commands:
                flags = [f for f, on in (("abortable", c.abortable), ("suspendable", c.suspendable)) if on]
                out.append(f"    {c.name}" + (f"  [{', '.join(flags)}]" if flags else "")
                           + (f"  {c.description}" if c.description else ""))
                if c.parameters:
                    out += table(["#", "parameter", "type", "unit", "range", "allowed", "default", "description"],
                                 [[str(i), p.name, p.type, p.unit or "-", _range(p),
                                   ", ".join(p.allowed) or "-", _default(p), p.description]
                                  for i, p in enumerate(c.parameters, 1)], indent=6)
    pubs = loaded.publications
    out += ["", "Telemetry"]
    out += table(["topic", "type", "role", "rate", "QoS"],
                 [[p.topic, p.type, p.role, _rate(p), p.qos] for p in pubs])
    out += _details(spec, pubs)
    if loaded.streams:
        out += ["", "Setpoint streams (DEADLINE and LIVELINESS QoS, outside the command queue)"]
        out += table(["stream", "dir", "type", "topic", "partition", "rate", "deadline", "lease", "on loss", "QoS"],
                     [[s.name, s.direction, s.type, s.topic, s.partition, f"{s.rate:g} Hz", f"{s.deadline_ms:g} ms",
                       f"{s.liveliness_ms:g} ms", s.on_loss, s.profile] for s in loaded.streams])
    if spec.native is not None:
        n = spec.native
        out += ["", "Native passthrough",
                f"  subsystem '{n.subsystem}', command '{n.command}'({n.parameter}: RAPID_STRING): "
                + (n.description or "the text is passed to the asset unchanged")]
    ac = spec.access_control
    if ac is not None:
        out += ["", f"Access control (sources not listed: {ac.default})"]
        out += table(["source", "may send"], [[r.source, ", ".join(r.allow)] for r in ac.rules])
    if loaded.ros2 is not None:
        out += _ros2(loaded)
    return "\n".join(visible(line) for line in "\n".join(out).split("\n")) + "\n"


def _ros2_source(conv: str, source, names: list[str]) -> str:
    """A command field's filling as the descriptor writes it (`names`: the command's parameters)."""
    if conv == "const":
        return repr(source)

    def ref(r) -> str:
        if r is None:
            return "0"
        if isinstance(r, int):
            return names[r]
        index, element, scale = r
        text = names[index] + (f"[{element}]" if element is not None else "")
        return text if scale == 1 else f"{text} x {scale:g}"
    if conv == "quat_euler":
        return "quaternion of " + ", ".join(f"{k} {ref(r)}" for k, r in zip(("roll", "pitch", "yaw"), source)
                                            if r is not None)
    return ", ".join(ref(r) for r in source) + {"quat_rpy": " (roll, pitch, yaw)", "quat_m33": " (rotation matrix)"
                                                }.get(conv, "")


def _ros2(loaded: LoadedAsset) -> list[str]:
    """The ros2: section as the generated bridge will serve it (docs/ros2.md)."""
    m = loaded.ros2
    assert m is not None
    types = {s.name: loaded.types.get(s.type) for s in loaded.subsystems}
    out = ["", f"ROS 2 (node {m['node']}; python -m <package>.ros2)"]
    feeds = []
    for f in m["telemetry"]:
        how = ""
        if f["feeds"] == "joint":
            how = f"{len(f['joints'])} joints by name"
        elif f["feeds"] == "position":
            how = f"pose {f['pose'] or 'message'} as {f['encoding']}" + \
                (f"; twist {f['twist']} turned into the pose's frame" if f["twist"] else "")
        elif f["feeds"] == "agent":
            how = "; ".join(f"{v[0]} <- " + (f"yaw of {v[1]}" if v[2] == "yaw" else v[1])
                            + (f" x {v[3]:g}" if len(v) > 3 and v[3] != 1 else "") for v in f["values"])
        feeds.append([f["topic"], f["type"], f"{f['feeds']} {f['index']}", how])
    if feeds:
        out += ["  telemetry (ROS 2 -> RAPID)"]
        out += table(["topic", "type", "feeds", "how"], feeds, indent=4)
    rows = []
    for name, c in m["commands"].items():
        doing = c.get("publish") or c.get("call") or c.get("action")
        kind = "publish" if "publish" in c else "call" if "call" in c else "action"
        target = doing.get("topic") or doing.get("service") or doing.get("action")
        sub, _, cname = name.partition("/")
        t = types.get(sub)
        cmd = next((x for x in (t.commands if t is not None else ()) if x.name == cname), None)
        names = [q.name for q in cmd.parameters] if cmd is not None else []
        fields = "; ".join(f"{path} <- {_ros2_source(conv, src, names)}" for path, conv, src in doing["fields"]) or "-"
        extra = []
        if c.get("until"):
            extra.append(f"until {c['until']['field']} == {c['until']['equals']!r} on {c['until']['topic']}")
        if c.get("cancel"):
            extra.append(f"cancel: {c['cancel']['topic']}")
        rows.append([name, f"{kind} {target}", doing["type"], fields + ("; " + "; ".join(extra) if extra else "")])
    if rows:
        out += ["  commands (RAPID -> ROS 2)"]
        out += table(["command", "does", "type", "fields"], rows, indent=4)
    if m["streams"]:
        out += ["  streams (RAPID -> ROS 2)"]
        out += table(["stream", "topic", "type"], [[st["stream"], st["ros2"]["topic"], st["ros2"]["type"]]
                                                   for st in m["streams"]], indent=4)
    if m["ground"] is not None:
        g = m["ground"]
        out += [f"  ground (RAPID -> ROS 2): node {g['node']}, namespace {g['namespace'] or '/'}"]
    return out


def _details(spec, pubs) -> list[str]:
    out: list[str] = []
    topic_of: dict[int, str] = {}  # config topic (or the only one)
    data_topic_of: dict[int, str] = {}  # sample/state topic
    for p in pubs:
        if p.source is not None:
            topic_of.setdefault(id(p.source), p.topic)
            if p.role != "config":
                data_topic_of.setdefault(id(p.source), p.topic)
    values = []
    for t in spec.telemetry:
        topic = topic_of.get(id(t), "?")
        if isinstance(t, PositionTelemetry):
            out += ["", f"Position {topic}: frame '{t.frame}', pose {t.pose_encoding}, "
                    f"velocity {t.velocity_encoding}"]
        if isinstance(t, ImageTelemetry):
            size = f", {t.width}x{t.height}" if t.width and t.height else ""
            out += ["", f"Images {topic}: sensor '{t.sensor}'"
                    + (f" ({t.sensor_type})" if t.sensor_type else "") + f", {t.mime}{size}"]
        if isinstance(t, JointTelemetry):
            fields = f"; fields {', '.join(t.fields)}" if t.fields else ""
            out += ["", f"Joints {topic}: group '{t.group}', {len(t.joints)} joints{fields}"]
            out += table(["#", "frame", "dof", "unit", "range"],
                         [[str(i), j.frame, j.dof, j.unit or "-", _range(j)] for i, j in enumerate(t.joints)])
        if isinstance(t, (AgentTelemetry, PositionTelemetry)):
            values += [[data_topic_of.get(id(t), topic), str(i), v.name, v.type, v.unit or "-", _range(v),
                        _default(v), _threshold(v.warning), _threshold(v.critical)] for i, v in enumerate(t.values)]
    if values:
        out += ["", "Values (index i of the sample's or state's values; initial value in the config)"]
        out += table(["topic", "#", "key", "type", "unit", "range", "initial", "warning", "critical"], values)
    return out


# -- as data (describe --json): what the tables above show, field by field -----------------------
def _typed(v: TypedValue) -> dict:
    return {"name": v.name, "type": v.type, "unit": v.unit, "min": v.min, "max": v.max,
            "allowed": list(v.allowed), "default": v.default if v.has_default else None,
            "has_default": v.has_default, "description": v.description}


def _limits(t: Threshold | None) -> dict | None:
    return None if t is None else {"below": t.below, "above": t.above}


def describe_data(loaded: LoadedAsset) -> dict:
    spec = loaded.spec
    subs = loaded.subsystems
    pubs = loaded.publications
    telemetry = []
    for t in spec.telemetry:
        entry: dict[str, object] = {"kind": type(t).__name__.removesuffix("Telemetry").lower(),
                 "topics": [p.topic for p in pubs if p.source is t]}
        if isinstance(t, PositionTelemetry):
            entry.update(frame=t.frame, pose_encoding=t.pose_encoding, velocity_encoding=t.velocity_encoding)
        if isinstance(t, ImageTelemetry):
            entry.update(sensor=t.sensor, sensor_type=t.sensor_type, mime=t.mime, width=t.width, height=t.height)
        if isinstance(t, JointTelemetry):
            entry.update(group=t.group, fields=list(t.fields), joints=[
                {"frame": j.frame, "dof": j.dof, "unit": j.unit, "min": j.min, "max": j.max} for j in t.joints])
        if isinstance(t, (AgentTelemetry, PositionTelemetry)):
            entry["values"] = [dict(_typed(v), warning=_limits(v.warning), critical=_limits(v.critical))
                               for v in t.values]
        telemetry.append(entry)
    ac = spec.access_control
    return {
        "name": spec.name, "kind": spec.kind, "description": spec.description, "tags": list(spec.tags),
        "domain": spec.domain, "partition": spec.partition,
        "subsystems": [{"name": s.name, "type": s.type, "description": s.description} for s in subs],
        "command_dictionary": [
            {"type": t.name, "standard": t.standard, "subsystems": [s.name for s in subs if s.type == t.name],
             "commands": [{"name": c.name, "description": c.description, "abortable": c.abortable,
                           "suspendable": c.suspendable, "parameters": [_typed(p) for p in c.parameters]}
                          for c in t.commands]}
            for t in loaded.used_types],
        "publications": [{"topic": p.topic, "type": p.type, "role": p.role, "rate": p.rate, "qos": p.qos}
                         for p in pubs],
        "telemetry": telemetry,
        "streams": [{"name": s.name, "direction": s.direction, "type": s.type, "topic": s.topic,
                     "partition": s.partition, "rate": s.rate, "deadline_ms": s.deadline_ms,
                     "liveliness_ms": s.liveliness_ms, "on_loss": s.on_loss, "subsystem": s.subsystem,
                     "state_key": s.state_key, "missed_key": s.missed_key, "qos": s.profile,
                     "description": s.description} for s in loaded.streams],
        "native": None if spec.native is None else {
            "subsystem": spec.native.subsystem, "command": spec.native.command,
            "parameter": spec.native.parameter, "description": spec.native.description},
        "access_control": None if ac is None else {
            "default": ac.default, "rules": [{"source": r.source, "allow": list(r.allow)} for r in ac.rules]},
        "ros2": loaded.ros2,  # the checked section as the generated ros2_map.py holds it (None without one)
    }
