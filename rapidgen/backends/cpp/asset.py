"""The asset as C++ constants (`include/<package>/asset.hpp`): its name, domain and
partition, every topic it publishes (role, type, QoS profile) and every computed config
as a function returning the message, so a C++ robot publishes its configs (command
dictionary included: it is the CommandConfig) without rapidgen at run time.

Config values come in the value form of docs/cdr-and-vectors.md (struct members by IDL
name, unions as discriminator + value, enums by name); value_expr turns one into a C++
expression of the generated types.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rapidgen.backends.cpp import namer
from rapidgen.backends.typewalk import Unsupported
from rapidgen.backends.escape import cpp_str
from rapidgen.model import ir

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset
    from rapidgen.backends.cpp.view import Builder


@dataclass
class PublicationView:
    role: str
    type: str
    topic: str
    qos: str


@dataclass
class ConfigView:
    function: str
    topic: str
    type: str  # qualified C++ type
    expr: str


@dataclass
class AssetView:
    name: str
    kind: str
    domain: int
    partition: str
    publications: list[PublicationView]
    configs: list[ConfigView]


def build(loaded: "LoadedAsset", b: "Builder") -> AssetView:
    spec = loaded.spec
    pubs = [PublicationView(cpp_str(p.role), cpp_str(p.type), cpp_str(p.topic), cpp_str(p.qos))
            for p in loaded.publications]
    scope = namer.Scope("asset functions")
    out = []
    for topic, (type_name, value) in loaded.configs.items():
        fn = scope.claim("config_" + (re.sub(r"[^A-Za-z0-9_]", "_", topic) or "topic"), topic)
        out.append(ConfigView(fn, cpp_str(topic), b.qualified(type_name),
                              value_expr(b, ir.TypeRef(type_name, "struct"), value, 1)))
    return AssetView(cpp_str(spec.name), cpp_str(spec.kind), int(spec.domain), cpp_str(spec.partition or ""),
                     pubs, out)


def value_expr(b: "Builder", t: ir.Type, value: object, depth: int) -> str:
    """A C++ expression of type t holding the value-form `value`."""
    if depth > 64:
        raise Unsupported("config value nested too deeply")
    r = b.types.real(t)
    pad = "    " * depth
    if isinstance(r, ir.Primitive):
        return b.types.literal(value, r, None)  # type: ignore[arg-type]
    if isinstance(r, ir.String):
        return f"std::string({cpp_str(value)}, {len(str(value).encode())}u)"  # type: ignore[arg-type]
    if isinstance(r, (ir.Sequence, ir.Array)):
        items = list(value) if not isinstance(value, (bytes, bytearray)) else list(value)  # type: ignore[call-overload]
        inner = r.element if isinstance(r, ir.Sequence) or len(r.dims) == 1 else ir.Array(r.element, r.dims[1:])
        parts = [value_expr(b, inner, v, depth + 1) for v in items]
        ctype = b.types.cpp(r, None)  # type: ignore[arg-type]
        return ctype + "{" + ", ".join(parts) + "}"
    d = b.types.decl(r)
    if isinstance(d, ir.Enum):
        name = value if isinstance(value, str) else next(e.name for e in d.enumerators if e.value == value)
        return f"{b.qualified(d.scoped_name)}::{b.enum_names[d.scoped_name][name]}"
    if isinstance(d, ir.Struct):
        names = b._member_names(d)
        lines = [f"{pad}    {b.qualified(d.scoped_name)} v;"]
        for m in b.model.all_members(d):
            if isinstance(value, dict) and m.name in value:
                lines.append(f"{pad}    v.{names[m.name]} = {value_expr(b, m.type, value[m.name], depth + 1)};")
        return "[] {\n" + "\n".join(lines) + f"\n{pad}    return v;\n{pad}}}()"
    if isinstance(d, ir.Union) and isinstance(value, dict):
        disc = value["discriminator"]
        dreal = b.types.real(d.discriminator)
        ddecl = b.types.decl(dreal)
        key = (False, next(e.value for e in ddecl.enumerators if e.name == disc)) if isinstance(ddecl, ir.Enum) \
            else ir.label_key(disc)
        case = next((c for c in d.cases if any(ir.label_key(lab) == key for lab in c.labels)), None)
        case = case or next((c for c in d.cases if c.is_default), None)
        if case is None or "value" not in value:
            raise Unsupported(f"config value of {d.scoped_name} selects no member")
        names = b._union_names(d)
        return (f"[] {{\n{pad}    {b.qualified(d.scoped_name)} v;\n{pad}    v.{names[case.member.name]}("
                f"{value_expr(b, case.member.type, value['value'], depth + 1)});\n{pad}    return v;\n{pad}}}()")
    raise Unsupported(f"no C++ value for {t}")
