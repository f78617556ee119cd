"""The asset as declarative data for the generated package (issue 10).

    <package>/asset_tables.py   the command dictionary (units, ranges, allowed values,
                                defaults, handler method names), computed configs, topics,
                                telemetry declarations, access rules: literals only
    <package>/handlers.py       the user's handlers, written once (user_owned), one typed
                                method per command, stubs answering "not implemented"
    <package>/bridge.py         `python -m <package>.bridge [--simulate]`: the runtime on
                                these tables
    <package>/qos_files/...     the QoS files (package data), so RapidQos() works after
                                `pip install`

The behaviour lives in the rapid_runtime distribution (runtime/); nothing here is
protocol logic. Every input string reaches the files through escape.py (py_str,
docstring, comment) or the literal printer below, which uses py_str.
"""
from __future__ import annotations

import keyword
import math
import re

from rapidgen.asset.spec import (AgentTelemetry, ImageTelemetry, JointTelemetry, PositionTelemetry,
                                 TextTelemetry, TypedValue)
from rapidgen.backends.base import GeneratedFile
from rapidgen.backends.escape import py_str
from rapidgen.backends.templating import render

FORMAT = 1  # rapid_runtime.tables.FORMAT
QOS_FOLDER = "qos_files"
PY_TYPES = {"RAPID_BOOL": "bool", "RAPID_DOUBLE": "float", "RAPID_FLOAT": "float", "RAPID_INT": "int",
            "RAPID_LONGLONG": "int", "RAPID_STRING": "str", "RAPID_VEC3d": "list[float]",
            "RAPID_MAT33f": "list[float]"}
RESERVED_ARGS = {"self", "ctx"}


def literal(value: object, indent: int = 0) -> str:
    """A Python literal of plain data (str through py_str), one item per line when long."""
    if isinstance(value, str):
        return py_str(value)
    if value is None or isinstance(value, bool) or isinstance(value, int):
        return repr(value)
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else f'float({py_str(repr(value))})'
    if isinstance(value, (list, tuple)):
        parts, open_, close = [literal(v, indent + 4) for v in value], "[", "]"
    elif isinstance(value, dict):
        parts = [f"{literal(k)}: {literal(v, indent + 4)}" for k, v in value.items()]
        open_, close = "{", "}"
    else:
        raise TypeError(f"no literal for {type(value).__name__}")
    flat = open_ + ", ".join(parts) + close
    if len(flat) + indent <= 100 and "\n" not in flat:
        return flat
    pad = " " * (indent + 4)
    return open_ + "\n" + "".join(f"{pad}{p},\n" for p in parts) + " " * indent + close


def snake(name: str) -> str:
    """A Python identifier from any descriptor name: camelCase -> camel_case, others -> '_'."""
    s = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", name)
    s = re.sub(r"([A-Z]+)([A-Z][a-z])", r"\1_\2", s)
    s = re.sub(r"\W+", "_", s.encode("ascii", "ignore").decode()).strip("_").lower()
    s = re.sub(r"_+", "_", s)
    if not s or s[0].isdigit():
        s = "x_" + s
    return s + "_" if keyword.iskeyword(s) or s in RESERVED_ARGS else s


def _unique(name: str, taken: set[str]) -> str:
    out, n = name, 2
    while out in taken:
        out, n = f"{name}_{n}", n + 1
    taken.add(out)
    return out


def _typed(v: TypedValue, arg: str | None = None) -> dict:
    d = {"name": v.name, "type": v.type, "unit": v.unit, "min": v.min, "max": v.max,
         "allowed": list(v.allowed), "default": _plain(v.default), "has_default": v.has_default,
         "description": v.description}
    if arg is not None:
        d = {"name": v.name, "arg": arg, **{k: x for k, x in d.items() if k != "name"}}
    return d


def _plain(v: object) -> object:
    return list(v) if isinstance(v, tuple) else v


def tables(loaded) -> dict:
    """Everything the runtime needs to know about the asset, as plain data."""
    spec = loaded.spec
    methods: set[str] = set()
    commands = {}
    for t in loaded.used_types:
        cmds = {}
        for c in t.commands:
            args: set[str] = set()
            cmds[c.name] = {
                "method": _unique(f"{snake(t.name)}_{snake(c.name)}", methods),
                "description": c.description, "abortable": c.abortable, "suspendable": c.suspendable,
                "standard": t.standard,
                "parameters": [_typed(p, _unique(snake(p.name), args)) for p in c.parameters]}
            if c.stop_timeout_ms is not None:  # declared only: absent means the bridge's default
                cmds[c.name]["stop_timeout_ms"] = c.stop_timeout_ms
        commands[t.name] = cmds
    access = None
    if spec.access_control is not None:
        access = {"default": spec.access_control.default,
                  "rules": [{"source": r.source, "allow": list(r.allow)} for r in spec.access_control.rules]}
    pubs = loaded.publications
    telemetry = []
    for t, topics in zip(spec.telemetry, loaded.telemetry_topics):
        entry = {"kind": t.kind, "topics": topics, "rate": t.rate, "subsystem": t.subsystem,
                 "values": [_typed(v) for v in getattr(t, "values", ())]}
        if t.stale_after_ms is not None:  # declared only: absent means derived from the rate (rapid_runtime.telemetry)
            entry["stale_after_ms"] = t.stale_after_ms
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
        elif not isinstance(t, AgentTelemetry):
            entry.update(types={m.role: m.type for m in t.messages})
        telemetry.append(entry)
    return {
        "FORMAT": FORMAT,
        "ASSET": {"name": spec.name, "kind": spec.kind, "description": spec.description, "tags": list(spec.tags),
                  "domain": spec.domain, "partition": spec.partition},
        "SUBSYSTEMS": {s.name: s.type for s in loaded.subsystems},
        "COMMANDS": commands,
        "ACCESS": access,
        "CONFIGS": {topic: {"type": ty, "value": value} for topic, (ty, value) in loaded.configs.items()},
        "PUBLICATIONS": [{"role": p.role, "type": p.type, "topic": p.topic, "qos": p.qos, "rate": p.rate}
                         for p in pubs],
        "TELEMETRY": telemetry,
    }


def _handler_views(data: dict) -> list[dict]:
    """One handler method per command the user implements (built-ins are the runtime's)."""
    subs_of: dict[str, list[str]] = {}
    for sub, ty in data["SUBSYSTEMS"].items():
        subs_of.setdefault(ty, []).append(sub)
    out = []
    for ty, cmds in data["COMMANDS"].items():
        for name, c in cmds.items():
            if c["standard"] and (ty, name) in RUNTIME_BUILTINS:
                continue
            params = []
            for p in c["parameters"]:
                limits = []
                if p["unit"]:
                    limits.append(f"[{p['unit']}]")
                if p["min"] is not None or p["max"] is not None:
                    limits.append(f"range [{p['min'] if p['min'] is not None else '-inf'}, "
                                  f"{p['max'] if p['max'] is not None else 'inf'}]")
                if p["allowed"]:
                    limits.append("one of " + ", ".join(map(str, p["allowed"])))
                if p["has_default"]:
                    limits.append(f"default {p['default']!r}")
                params.append({"arg": p["arg"], "pytype": PY_TYPES.get(p["type"], "object"),
                               "doc": " ".join([f"{p['arg']} ({p['name'] + ', ' if p['name'] != p['arg'] else ''}{p['type']})",
                                                 *limits])
                                      + (f": {p['description']}" if p["description"] else "")})
            flags = [f for f in ("abortable", "suspendable") if c[f]]
            out.append({"method": c["method"], "params": params,
                        "title": f"{ty}/{name}: {c['description'] or 'no description'}",
                        "where": f"Subsystems: {', '.join(subs_of.get(ty, []))}."
                                 + (f" {' and '.join(flags).capitalize()}: watch ctx.cancelled." if flags else ""),
                        "stop_first": (ty, name) == ("Mobility", "stopAllMotion")})
    return out


# Standard commands the runtime answers itself (rapid_runtime.manager.BUILTINS, less
# stopAllMotion: the runtime cancels motion, then the handler stops the hardware).
RUNTIME_BUILTINS = {("Admin", "echo"), ("Admin", "noOp"), ("Admin", "shutdown"), ("Queue", "cancelAll"),
                    ("AccessControl", "requestControl"), ("AccessControl", "grabControl"),
                    ("AccessControl", "releaseControl"), ("AccessControl", "transferControl")}


def runtime_view(package: str) -> dict:
    """What pyproject.toml adds for an asset package: the QoS files as data (every package
    requires the runtime: view.RUNTIME_REQUIREMENT)."""
    return {"package": package,
            "package_data": [f"{QOS_FOLDER}/*.json", f"{QOS_FOLDER}/*/*.xml"]}


def generate(loaded, package: str, header: str) -> list[GeneratedFile]:
    data = tables(loaded)
    body = "\n\n".join(f"{name} = {literal(value)}" for name, value in data.items())
    name = loaded.spec.name
    files = [
        GeneratedFile(f"{package}/asset_tables.py",
                      render("python", "asset_tables.py.j2", header=header, asset=name, body=body)),
        GeneratedFile(f"{package}/bridge.py", render("python", "bridge.py.j2", header=header, package=package,
                                                     asset=name)),
        GeneratedFile(f"{package}/handlers.py",
                      render("python", "handlers.py.j2", package=package, asset=name,
                             methods=_handler_views(data)), user_owned=True),
    ]
    return files


def with_qos_files(files: list[GeneratedFile], qos_files: list[GeneratedFile]) -> list[GeneratedFile]:
    """The python target's files plus the qos target's under <package>/qos_files/ (the
    driver calls this: a back end imports no other back end)."""
    tables_file = next((f.path for f in files if f.path.endswith("/asset_tables.py")), None)
    if tables_file is None:
        return files
    package = tables_file.rsplit("/", 1)[0]
    extra = [GeneratedFile(f"{package}/{QOS_FOLDER}/{f.path}", f.content) for f in qos_files]
    return sorted(files + extra, key=lambda f: f.path)
