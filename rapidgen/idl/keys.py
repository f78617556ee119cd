"""Instance keys: `@key`, trailing `//@key` (RTI) and `#pragma keylist` (Cyclone/OpenSplice).

A struct's key is the list of key paths, base keys first. A key member whose type is a
struct contributes that struct's own keys (`hdr` -> `hdr.srcName`, `hdr.assetName`), or,
when that struct declares none, all of its members, as DDS-XTypes specifies.
"""
from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from rapidgen.diagnostics import DiagnosticSink, did_you_mean
from rapidgen.idl import ast
from rapidgen.model import ir

if TYPE_CHECKING:
    from rapidgen.idl.resolve import Resolver


def apply_keylists(decls: list[ir.Declaration], pragmas: list[tuple[ast.KeylistPragma, tuple[str, ...]]],
                   resolver: "Resolver", sink: DiagnosticSink) -> list[ir.Declaration]:
    """Mark `#pragma keylist` members as keys; the struct's key paths become the listed ones."""
    index = {d.scoped_name: i for i, d in enumerate(decls)}
    structs = {d.scoped_name: d for d in decls if isinstance(d, ir.Struct)}
    typedefs = {d.scoped_name: d for d in decls if isinstance(d, ir.Typedef)}
    for pragma, scope in pragmas:
        sym = resolver.lookup(pragma.type, scope)
        if sym is None:
            resolver._unknown(pragma.type, scope, "type", frozenset({"struct"}))
            continue
        struct = structs.get(sym.scoped)
        if struct is None:
            sink.error("RG0310", f"#pragma keylist names '{pragma.type}', which is not a struct", pragma.type.loc)
            continue
        paths: list[str] = []
        own = {m.name for m in struct.members}
        for path, loc in pragma.members:
            parts = path.split(".")
            owner: ir.Struct | None = struct
            ok = True
            for i, part in enumerate(parts):
                members = {m.name: m for m in ir.flatten(owner, structs.get)} if owner else {}
                if part not in members:
                    where = owner.scoped_name if owner else ".".join(parts[:i])
                    sink.error("RG0310", f"#pragma keylist: '{where}' has no member '{part}'", loc,
                               did_you_mean(part, members))
                    ok = False
                    break
                t = ir.unalias(members[part].type, typedefs.get)
                owner = structs.get(t.name) if isinstance(t, ir.TypeRef) else None
            if ok:
                paths.append(path)
        keyed = {p.split(".")[0] for p in paths}
        keyed_members = tuple(replace(m, key=True) if m.name in keyed and m.name in own else m
                              for m in struct.members)
        updated = replace(struct, members=keyed_members, keys=tuple(paths))
        structs[struct.scoped_name] = updated
        decls[index[struct.scoped_name]] = updated
    return decls


def compute_keys(decls: list[ir.Declaration], sink: DiagnosticSink) -> list[ir.Declaration]:
    structs = {d.scoped_name: d for d in decls if isinstance(d, ir.Struct)}
    typedefs = {d.scoped_name: d for d in decls if isinstance(d, ir.Typedef)}
    memo: dict[str, tuple[str, ...]] = {}

    def expand(prefix: str, t: ir.Type, depth: int) -> list[str]:
        real = ir.unalias(t, typedefs.get)
        if isinstance(real, ir.TypeRef) and real.name in structs and depth < 32:
            inner = keys_of(real.name, depth + 1)
            if inner:
                return [f"{prefix}.{k}" for k in inner]
            out: list[str] = []
            for m in ir.flatten(structs[real.name], structs.get):
                out.extend(expand(f"{prefix}.{m.name}", m.type, depth + 1))
            return out
        return [prefix]

    def keys_of(name: str, depth: int = 0) -> tuple[str, ...]:
        if name in memo:
            return memo[name]
        memo[name] = ()  # guards against cycles (already reported by the recursion check)
        s = structs[name]
        if s.keys:  # from #pragma keylist
            memo[name] = s.keys
            return s.keys
        result: list[str] = list(keys_of(s.base, depth)) if s.base in structs else []
        for m in s.members:
            if m.key:
                result.extend(expand(m.name, m.type, depth))
        memo[name] = tuple(result)
        return memo[name]

    out: list[ir.Declaration] = []
    for d in decls:
        if isinstance(d, ir.Struct):
            keys = keys_of(d.scoped_name)
            out.append(d if keys == d.keys else replace(d, keys=keys))
        else:
            out.append(d)
    return out
