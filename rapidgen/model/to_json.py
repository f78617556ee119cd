"""The resolved model as JSON (`rapidgen ir`): stable, sorted where order is free."""
from __future__ import annotations

import json
from decimal import Decimal

from rapidgen.model import ir


def _value(v: object) -> object:
    if isinstance(v, ir.EnumValue):
        return {"enum": v.enum, "name": v.name, "value": v.value}
    if isinstance(v, Decimal):
        return {"fixed": str(v)}
    if isinstance(v, float) and (v != v or v in (float("inf"), float("-inf"))):
        return {"float": str(v)}
    return v


def _annotations(anns: tuple[ir.Annotation, ...]) -> list[dict]:
    return [{"name": a.name, "params": {k: _value(v) for k, v in a.params}} for a in anns]


def _member(m: ir.Member) -> dict:
    out: dict[str, object] = {"name": m.name, "type": str(m.type)}
    if m.key:
        out["key"] = True
    if m.optional:
        out["optional"] = True
    if m.external:
        out["external"] = True
    if m.id is not None:
        out["id"] = m.id
    out["member_id"] = m.member_id
    if m.default is not None:
        out["default"] = _value(m.default)
    if m.annotations:
        out["annotations"] = _annotations(m.annotations)
    return out


def declaration(d: ir.Declaration, loc: bool = True) -> dict:
    out: dict[str, object] = {"name": d.scoped_name, "kind": d.kind}
    if isinstance(d, ir.Struct):
        out.update(base=d.base, origin=d.origin, extensibility=d.extensibility,
                   members=[_member(m) for m in d.members], keys=list(d.keys))
        if d.nested:
            out["nested"] = True
        if d.autoid != "SEQUENTIAL":
            out["autoid"] = d.autoid
    elif isinstance(d, ir.Union):
        out.update(discriminator=str(d.discriminator), extensibility=d.extensibility,
                   cases=[{"labels": [_value(v) for v in c.labels], "default": c.is_default,
                           **_member(c.member)} for c in d.cases],
                   default_discriminator=_value(d.default_discriminator), default_case=d.default_case)
        if d.autoid != "SEQUENTIAL":
            out["autoid"] = d.autoid
    elif isinstance(d, ir.Enum):
        out.update(bit_bound=d.bit_bound,
                   enumerators=[{"name": e.name, "value": e.value} for e in d.enumerators],
                   default=d.default)
    elif isinstance(d, ir.Bitmask):
        out.update(bit_bound=d.bit_bound, values=[{"name": v.name, "position": v.position} for v in d.values])
    elif isinstance(d, ir.Bitset):
        out.update(base=d.base, fields=[{"name": f.name, "width": f.width, "type": str(f.type)} for f in d.fields])
    elif isinstance(d, ir.Typedef):
        out["type"] = str(d.type)
    elif isinstance(d, ir.Const):
        out.update(type=str(d.type), value=_value(d.value))
    if d.annotations:
        out["annotations"] = _annotations(d.annotations)
    if loc:
        out["loc"] = str(d.loc)
    return out


def model_to_dict(model: ir.Model, loc: bool = True) -> dict:
    return {
        "modules": [m.scoped_name for m in model.modules],
        "declarations": [declaration(d, loc) for d in model.declarations],
    }


def model_to_json(model: ir.Model, loc: bool = True) -> str:
    """One declaration per line: readable diffs, and the C JSON encoder (indent= is pure Python)."""
    data = model_to_dict(model, loc)
    decls = ",\n".join("    " + json.dumps(d, ensure_ascii=False) for d in data["declarations"])
    return ('{\n  "modules": ' + json.dumps(data["modules"], ensure_ascii=False) +
            ',\n  "declarations": [\n' + decls + ("\n" if decls else "") + "  ]\n}\n")
