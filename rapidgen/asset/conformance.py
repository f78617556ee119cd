"""The descriptor's `conformance:` section: what `rapidgen conform` may do to the asset.

    conformance:
      motion:            # commands that move the asset the runner may send, with their arguments
        - command: Mobility/simpleMove
          args: {frame: site, xyt: [0.5, 0, 0]}

Resolved to plain data, {"motion": {"Mobility/simpleMove": [(DataType, value), ...]}} with the
arguments in parameter order (a parameter left out is sent its default), on
LoadedAsset.conformance. The schema checks the shape; this module checks each item against
the asset (RG1318, located at the key or value): the command exists and moves the asset, every
argument names a parameter and fits its DataType, range and allowed values.
"""
from __future__ import annotations

import math
from typing import Any

from rapidgen.yamlread import YamlDoc
from rapidgen.diagnostics import DiagnosticSink

CODE = "RG1318"
MOTION_TYPE = "Mobility"
NOT_MOTION = frozenset({"stopAllMotion"})  # stops the asset: conform may always send it (ACC-06)
_VECTORS = {"RAPID_VEC3d": 3, "RAPID_MAT33f": 9}
_INTS = {"RAPID_INT": (-2**31, 2**31 - 1), "RAPID_LONGLONG": (-2**63, 2**63 - 1)}


def is_motion(subsystem_type: str, command: str) -> bool:
    """A command conform sends only when allowed: any command of a Mobility-type subsystem but
    stopAllMotion."""
    return subsystem_type == MOTION_TYPE and command not in NOT_MOTION


def _number(x: object) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def fit_error(p: Any, value: object) -> str | None:
    """Why value cannot be sent for parameter p (None when it can)."""
    t = p.type
    if t == "RAPID_STRING":
        if not isinstance(value, str):
            return "a string"
        if p.allowed and value not in p.allowed:
            return "one of " + ", ".join(p.allowed)
        return None
    if t == "RAPID_BOOL":
        return None if isinstance(value, bool) else "true or false"
    if t in _VECTORS:
        n = _VECTORS[t]
        if not isinstance(value, list) or len(value) != n or not all(_number(x) for x in value):
            return f"a list of {n} numbers"
        items = value
    elif t in _INTS:
        lo, hi = _INTS[t]
        if not (isinstance(value, int) and not isinstance(value, bool) and lo <= value <= hi):
            return f"a whole number ({t})"
        items = [value]
    elif t in ("RAPID_FLOAT", "RAPID_DOUBLE"):
        if not _number(value):
            return "a number"
        items = [value]
    else:
        return f"a {t} value (conform sends only strings, booleans, numbers and vectors)"
    if any((p.min is not None and x < p.min) or (p.max is not None and x > p.max) for x in items):
        return f"within [{p.min if p.min is not None else ''}, {p.max if p.max is not None else ''}]"
    return None


def _sent(p: Any, value: Any) -> object:
    if p.type in _VECTORS:
        return [float(x) for x in value]
    if p.type in ("RAPID_FLOAT", "RAPID_DOUBLE"):
        return float(value)
    return value


class _Reader:
    def __init__(self, doc: YamlDoc, loaded: Any, sink: DiagnosticSink) -> None:
        self.doc, self.loaded, self.sink = doc, loaded, sink

    def error(self, message: str, path: tuple, hint: str, key: bool = False) -> None:
        self.sink.error(CODE, message, self.doc.key_loc(path) if key else self.doc.loc(path), hint)

    def motion_commands(self) -> list[str]:
        out = []
        for sub in self.loaded.subsystems:
            t = self.loaded.types.get(sub.type)
            out += [f"{sub.name}/{c.name}" for c in (t.commands if t else ()) if is_motion(sub.type, c.name)]
        return out

    def item(self, item: dict, path: tuple) -> tuple[str, list] | None:
        name = item["command"]
        sub_name, slash, cname = name.partition("/")
        subs = {s.name: s for s in self.loaded.subsystems}
        moving = self.motion_commands()
        hint = ("the asset's commands that move it: " + ", ".join(moving)) if moving else \
            "the asset has no Mobility subsystem: conform sends nothing that moves it, leave the section out"
        if not slash or sub_name not in subs:
            self.error(f"'{name}' names no subsystem of the asset", path + ("command",), hint)
            return None
        sub = subs[sub_name]
        t = self.loaded.types.get(sub.type)
        cmd = next((c for c in (t.commands if t else ()) if c.name == cname), None)
        if cmd is None:
            self.error(f"subsystem '{sub_name}' has no command '{cname}'", path + ("command",), hint)
            return None
        if not is_motion(sub.type, cname):
            self.error(f"'{name}' does not move the asset: conform sends it without leave", path + ("command",),
                       hint)
            return None
        args = item.get("args") or {}
        params = {p.name: p for p in cmd.parameters}
        ok = True
        for k, v in args.items():
            p = params.get(k)
            if p is None:
                self.error(f"'{name}' has no parameter '{k}'", path + ("args", k), "its parameters: "
                           + (", ".join(params) or "none"), key=True)
                ok = False
                continue
            why = fit_error(p, v)
            if why is not None:
                self.error(f"{name} {k}={v!r} cannot be sent", path + ("args", k), f"{k} ({p.type}) takes {why}")
                ok = False
        missing = [p.name for p in cmd.parameters if p.name not in args and not p.has_default]
        if missing:
            self.error(f"'{name}' needs a value for {', '.join(missing)}", path + ("command",),
                       "add it under args: " + ", ".join(f"{m}: ..." for m in missing))
            ok = False
        if not ok:
            return None
        return name, [(p.type, _sent(p, args[p.name] if p.name in args else p.default)) for p in cmd.parameters]

    def read(self, section: dict) -> dict:
        motion: dict[str, list] = {}
        where: dict[str, int] = {}
        for i, item in enumerate(section.get("motion") or []):
            got = self.item(item, ("conformance", "motion", i))
            if got is None:
                continue
            name, args = got
            if name in motion:
                self.error(f"'{name}' is listed twice", ("conformance", "motion", i, "command"),
                           f"first at line {self.doc.loc(('conformance', 'motion', where[name])).line}: keep one")
                continue
            motion[name], where[name] = args, i
        return {"motion": motion}


def read_conformance(doc: YamlDoc, loaded: Any, sink: DiagnosticSink) -> dict:
    """The checked section as plain data (items with errors left out, errors in the sink).
    `loaded` is the descriptor's LoadedAsset; the schema has checked the section's shape."""
    assert isinstance(doc.data, dict)
    return _Reader(doc, loaded, sink).read(doc.data.get("conformance") or {})
