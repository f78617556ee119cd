"""Plausible values of an asset's own (extension) types, for the messages a simulated robot
publishes: chosen by member name and type as the Python simulator's plausible() does, at the
site's origin. One rule for the C++ and Rust bridges' simulators (a module the back ends
share: tests/unit/test_layering.py's SHARED_BACKEND). `b` is the back end's builder: its
types (real()) and model."""
from __future__ import annotations

import re
from typing import Any

from rapidgen.model import ir

SITE = (37.41950, -122.06470, 10.0)  # the simulator's site origin (simulate.py): latitude, longitude, altitude
_GOOD = {"ok", "nominal", "good", "valid", "ready", "on", "enabled", "active", "locked", "normal", "3d", "running"}
_BAD = {"none", "unknown", "invalid", "error", "fail", "failed", "failure", "off", "fault", "no", "not", "disabled",
        "init", "undefined", "lost", "estop", "critical"}
_NUMBERS: list[tuple[set[str], float]] = [
    ({"lat", "latitude"}, SITE[0]), ({"lon", "lng", "long", "longitude"}, SITE[1]),
    ({"alt", "altitude", "elevation", "elev"}, SITE[2]), ({"dop", "hdop", "pdop", "vdop", "gdop"}, 0.9),
    ({"sat", "sats", "satellites", "satellite", "svs"}, 9), ({"temperature", "temp"}, 21.5),
    ({"voltage", "volt", "volts"}, 28.0), ({"current", "amps", "amp"}, 1.2), ({"charge", "percent", "soc"}, 80.0),
    ({"accuracy", "sigma", "std", "stddev", "uncertainty"}, 0.5), ({"count", "num", "number"}, 1)]
_TEXTS: list[tuple[set[str], str | None]] = [({"datum"}, "WGS84"), ({"frame"}, "site"),
                                             ({"name", "asset", "source", "src"}, None), ({"unit", "units"}, "m")]
_ROTATION = {"rot", "rotation", "orientation", "attitude", "mat", "matrix"}
_INT_BITS = {"int8": (8, True), "int16": (16, True), "int32": (32, True), "int64": (64, True), "uint8": (8, False),
             "uint16": (16, False), "uint32": (32, False), "uint64": (64, False), "octet": (8, False)}


def words(name: str) -> set[str]:
    return {w.lower() for w in re.findall(r"[A-Z]?[a-z]+|[A-Z]+(?![a-z])|\d+[A-Za-z]*", name)}


def plausible(b: Any, d: ir.Struct, asset: str, depth: int) -> dict:
    """A struct's value form with plausible members, chosen by name and type as the Python
    simulator's plausible() does, at the site's origin (a static message: latitude,
    longitude and altitude of the site, 9 satellites, 21.5 degC, strings 'simulated' (datum
    WGS84, frame site, names the asset's), enumerators that say all is well, identity
    rotations). Sequences and unions keep their defaults; `hdr` is the publisher's."""
    out: dict[str, object] = {}
    for m in b.model.all_members(d):
        if m.name == "hdr" or depth > 6:
            continue
        v = _member_value(b, m.type, m.name, asset, depth)
        if v is not None:
            out[m.name] = v
    return out


def _member_value(b: Any, t: ir.Type, name: str, asset: str, depth: int) -> object:
    r = b.types.real(t)
    ws = words(name)
    if isinstance(r, ir.Primitive):
        if r.name == "boolean":
            return bool(ws & (_GOOD | {"fix", "lock", "healthy", "available", "valid"}))
        number = next((v for keys, v in _NUMBERS if ws & keys), 0.0)
        if r.name in ("float32", "float64"):
            return float(number)
        if r.name in _INT_BITS:
            bits, signed = _INT_BITS[r.name]
            lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
            return max(lo, min(hi, int(round(number))))
        return None
    if isinstance(r, ir.String):
        if r.wide:
            return None
        found = next(((v,) for keys, v in _TEXTS if ws & keys), ("simulated",))[0]
        s = (asset if found is None else found).encode("utf-8")
        return s[:r.bound].decode("utf-8", "ignore") if r.bound else s.decode("utf-8")
    if isinstance(r, ir.Array) and len(r.dims) == 1 and isinstance(b.types.real(r.element), ir.Primitive) and \
            b.types.real(r.element).name in ("float32", "float64"):
        if r.dims[0] == 9 and ws & _ROTATION:
            return [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        if r.dims[0] == 4 and ws & {"quat", "quaternion", "q"}:
            return [0.0, 0.0, 0.0, 1.0]
        return None
    if isinstance(r, ir.TypeRef):
        decl = b.types.decl(r)
        if isinstance(decl, ir.Enum) and decl.enumerators:
            good = [e for e in decl.enumerators if words(e.name) & _GOOD]
            fine = [e for e in decl.enumerators if not words(e.name) & _BAD]
            return (good or fine or list(decl.enumerators))[0].name
        if isinstance(decl, ir.Struct):
            return plausible(b, decl, asset, depth + 1)
    return None
