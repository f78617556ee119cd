"""Which member of a type differs: RAPID's generated class against the one a writer
announced (XTypes type information, rebuilt by cyclonedds.dynamic). Used by SPY-TYPE-01.

Cyclone matches a reader and a writer by XTypes assignability: a typedef and the plain type
it names are the same in a top-level member, but not inside a nested type (seen here: a
ParameterUnion whose vec3d is `double[3]` where RAPID has the Vec3d typedef does not
match). The walk follows the member types all the way down, strips typedefs at the top
level only, and names the first place that differs as `Type.member`.
"""
from __future__ import annotations

import typing

MAX_DEPTH = 32


def first_difference(ours: object, theirs: object) -> str | None:
    """'ParameterUnion.vec3d is double[3], RAPID's is Vec3d (...)', or None when alike."""
    return _Walk().types(ours, theirs, _short(ours), top=True, depth=0)


def _short(cls) -> str:
    name = getattr(cls, "__idl_typename__", None) or getattr(cls, "__name__", str(cls))
    return str(name).replace("::", ".").rsplit(".", 1)[-1]


def _members(cls) -> list[tuple[str, object]]:
    try:
        hints = typing.get_type_hints(cls, include_extras=True)
    except Exception:  # a dynamic class whose annotations do not resolve
        hints = dict(getattr(cls, "__annotations__", {}))
    return [(k, v) for k, v in hints.items() if not k.startswith("_")]


def _meta(t):
    """The cyclonedds description of an annotation: typedef, sequence, array, bounded_str,
    case, a primitive's name ('int32'), or the class itself (struct, union, enum, str, bool)."""
    while typing.get_origin(t) is typing.Annotated:
        meta = t.__metadata__[-1]
        if isinstance(meta, str) or hasattr(meta, "subtype") or hasattr(meta, "max_length"):
            t = meta
            break
        t = t.__origin__
    if typing.get_origin(t) is typing.Union:  # Optional[...] of a union case
        t = next(a for a in typing.get_args(t) if a is not type(None))
        return _meta(t)
    return t


def _kind(t) -> str:
    name = type(t).__name__
    if isinstance(t, str):
        return "primitive"
    if name in ("typedef", "sequence", "array", "bounded_str", "case", "default"):
        return name
    bases = {b.__name__ for b in getattr(t, "__mro__", ())}
    for kind in ("IdlStruct", "IdlUnion", "IdlEnum"):
        if kind in bases:
            return kind
    return "primitive"


def show(t) -> str:
    t = _meta(t)
    kind = _kind(t)
    if kind == "typedef":
        return _short_name(t.name)
    if kind == "sequence":
        return f"sequence<{show(t.subtype)}" + (f", {t.max_length}>" if t.max_length else ">")
    if kind == "array":
        return f"{show(t.subtype)}[{t.length}]"
    if kind == "bounded_str":
        return f"string<{t.max_length}>"
    if kind in ("case", "default"):
        return show(t.subtype)
    if isinstance(t, str):
        return {"float64": "double", "float32": "float", "int32": "long", "int64": "long long"}.get(t, t)
    if t is str:
        return "string"
    return _short(t) if hasattr(t, "__name__") else str(t)


def _short_name(name) -> str:
    return str(name).replace("::", ".").rsplit(".", 1)[-1]


class _Walk:
    def __init__(self) -> None:
        self.seen: set[tuple[int, int]] = set()

    def types(self, a, b, where: str, top: bool, depth: int) -> str | None:
        if depth > MAX_DEPTH:
            return None
        a, b = _meta(a), _meta(b)
        ka, kb = _kind(a), _kind(b)
        if ka in ("case", "default"):
            return self.types(a.subtype, b.subtype if kb in ("case", "default") else b, where, top, depth)
        if kb in ("case", "default"):
            return self.types(a, b.subtype, where, top, depth)
        if (ka == "typedef") != (kb == "typedef"):
            if not top:
                return (f"{where} is {show(b)}, RAPID's is {show(a)} (a typedef and the type it names "
                        "do not match inside a nested type)")
            return self.types(a.subtype if ka == "typedef" else a, b.subtype if kb == "typedef" else b,
                              where, top, depth)
        if ka == "typedef":
            if _short_name(a.name) != _short_name(b.name):
                return f"{where} is {show(b)}, RAPID's is {show(a)}"
            return self.types(a.subtype, b.subtype, where, top, depth + 1)
        if ka != kb:
            return f"{where} is {show(b)}, RAPID's is {show(a)}"
        if ka == "sequence":
            if a.max_length != b.max_length:
                return f"{where} is {show(b)}, RAPID's is {show(a)}"
            return self.types(a.subtype, b.subtype, where + "[]", False, depth + 1)
        if ka == "array":
            if a.length != b.length:
                return f"{where} is {show(b)}, RAPID's is {show(a)}"
            return self.types(a.subtype, b.subtype, where + "[]", False, depth + 1)
        if ka == "bounded_str":
            return None if a.max_length == b.max_length else f"{where} is {show(b)}, RAPID's is {show(a)}"
        if ka in ("IdlStruct", "IdlUnion"):
            return self.composite(a, b, depth)
        if ka == "IdlEnum":
            ea = [(e.name, e.value) for e in a]
            eb = [(e.name, e.value) for e in b]
            return None if ea == eb else f"{where}: enum {show(b)} has {len(eb)} enumerators, RAPID's {len(ea)}"
        same = a == b or show(a) == show(b)
        return None if same else f"{where} is {show(b)}, RAPID's is {show(a)}"

    def composite(self, a, b, depth: int) -> str | None:
        if (id(a), id(b)) in self.seen:
            return None
        self.seen.add((id(a), id(b)))
        name = _short(a)
        ma, mb = _members(a), _members(b)
        for i in range(max(len(ma), len(mb))):
            if i >= len(ma):
                return f"{name}: member #{i + 1} '{mb[i][0]}' is extra (RAPID's {name} has {len(ma)} members)"
            if i >= len(mb):
                return f"{name}.{ma[i][0]} ({show(ma[i][1])}) is missing"
            if ma[i][0] != mb[i][0]:
                return f"{name}: member #{i + 1} is '{mb[i][0]}', RAPID's is '{ma[i][0]}'"
            found = self.types(ma[i][1], mb[i][1], f"{name}.{ma[i][0]}", top=depth == 0, depth=depth + 1)
            if found:
                return found
        return None
