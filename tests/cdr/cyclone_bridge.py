"""cyclonedds-python types built from the Model, and values converted both ways.

An independent check of the reference encoder: cyclonedds serializes with its own
machinery (`cyclonedds.idl._machinery`). The classes here are made with
`make_idl_struct`/`make_idl_union`/`make_idl_enum` straight from the IR, so the check works
before (and independently of) the generated Python bindings.

cyclonedds 11 quirks handled here:
- `sequence[T, N]` with N > 65535 returns a TypeError object instead of a type: such
  sequences are declared unbounded (the bound is then not checked by cyclonedds).
- wchar is an int, char a one-character str written as a signed byte.
- no support for wstring, long double, fixed, bitsets, maps here, recursive types:
  `Unsupported` is raised.
- @bit_bound enums: XCDR2 by their size, but XCDR1 always 4 bytes (the reference
  encoder sizes them by @bit_bound in both; see docs/cdr-and-vectors.md).
"""
from __future__ import annotations

import dataclasses
import importlib
import pkgutil
import sys
import typing

from cyclonedds.idl import IdlEnum, IdlUnion, make_idl_enum, make_idl_struct, make_idl_union
from cyclonedds.idl import types as T

from rapidgen.model import ir
from rapidgen.cdr.typeinfo import CdrTypes


class Unsupported(Exception):
    pass


_PRIM = {"int8": T.int8, "uint8": T.uint8, "int16": T.int16, "uint16": T.uint16, "int32": T.int32,
         "uint32": T.uint32, "int64": T.int64, "uint64": T.uint64, "float32": T.float32, "float64": T.float64,
         "boolean": bool, "octet": T.uint8, "char8": T.char, "char16": T.wchar}


def _pyname(scoped: str) -> str:
    return scoped.replace("::", "_")


def generated_classes(package_dir: str, package: str) -> dict[str, type]:
    """Classes of a generated bindings package by IDL scoped name (from __idl_typename__)."""
    if package_dir not in sys.path:
        sys.path.insert(0, package_dir)
    root = importlib.import_module(package)
    out: dict[str, type] = {}
    for info in pkgutil.walk_packages(root.__path__, package + "."):
        mod = importlib.import_module(info.name)
        for obj in vars(mod).values():
            name = getattr(obj, "__idl_typename__", None)
            if isinstance(obj, type) and isinstance(name, str) and obj.__module__ == mod.__name__:
                out[name.replace(".", "::")] = obj
    return out


class CycloneTypes:
    """cyclonedds classes for the model's types: `classes` given (generated bindings), or
    made on demand with make_idl_struct & co. Values map to fields by position, so names
    a Python namer escaped still line up."""

    def __init__(self, model: ir.Model, classes: dict[str, type] | None = None) -> None:
        self.model = model
        self.t = CdrTypes(model)
        self.given = classes is not None
        self.classes: dict[str, type] = dict(classes or {})
        self.building: set[str] = set()

    # -- types ------------------------------------------------------------------------------
    def cls(self, scoped: str) -> type:
        if scoped in self.classes:
            return self.classes[scoped]
        if self.given:
            raise Unsupported(f"no generated class for {scoped}")
        if scoped in self.building:
            raise Unsupported(f"recursive type {scoped}")
        self.building.add(scoped)
        try:
            c = self._make(scoped)
        finally:
            self.building.discard(scoped)
        self.classes[scoped] = c
        return c

    def _make(self, scoped: str) -> type:
        d = self.model.get(scoped)
        if isinstance(d, ir.Enum):
            c = make_idl_enum(_pyname(scoped), scoped, {e.name: e.value for e in d.enumerators})
            if d.bit_bound != 32:
                c.__idl_annotations__["bit_bound"] = d.bit_bound  # (XCDR1: cyclonedds still writes 4 bytes)
        elif isinstance(d, ir.Struct):
            members = self.t.members(d)
            fields = {}
            fann: dict[str, dict] = {}
            for mi in members:
                m = mi.member
                ftype = self.hint(m.type)
                fields[m.name] = typing.Optional[ftype] if m.optional else ftype
                ann: dict[str, object] = {}
                if m.key:
                    ann["key"] = True
                if m.key and d.extensibility == "mutable":
                    ann["must_understand"] = True  # XTypes: key members carry the M flag
                ann["id"] = mi.id  # the model's member id (cyclonedds cannot hash a @hashid str)
                if ann:
                    fann[m.name] = ann
            c = make_idl_struct(_pyname(scoped), scoped, fields, field_annotations=fann)
            c.__idl_annotations__["extensibility"] = d.extensibility
        elif isinstance(d, ir.Union):
            disc = self.hint(d.discriminator)
            fields = {}
            for case in d.cases:
                sub = self.hint(case.member.type)
                if case.is_default:
                    fields[case.member.name] = T.default[sub]
                if case.labels:
                    labels = [self.label(d, lab) for lab in case.labels]
                    if case.is_default:
                        raise Unsupported("a case with labels and default")
                    fields[case.member.name] = T.case[labels, sub]
            c = make_idl_union(_pyname(scoped), scoped, fields, discriminator=disc)
            c.__idl_annotations__["extensibility"] = d.extensibility
        else:
            raise Unsupported(f"{scoped}: {getattr(d, 'kind', '?')}")
        return c

    def label(self, d: ir.Union, label: object) -> object:
        r = self.t.resolve(d.discriminator)
        if isinstance(label, ir.EnumValue):
            return self.cls(r.name)[label.name]  # type: ignore[union-attr,index]
        return label

    def hint(self, t: ir.Type) -> object:
        r = self.t.resolve(t)
        if isinstance(r, ir.Primitive):
            if r.name not in _PRIM:
                raise Unsupported(r.name)
            return _PRIM[r.name]
        if isinstance(r, ir.String):
            if r.wide:
                raise Unsupported("wstring")
            return T.bounded_str[r.bound] if r.bound else str
        if isinstance(r, ir.Sequence):
            elem = self.hint(r.element)
            if r.bound and r.bound <= 65535:
                return T.sequence[elem, r.bound]
            return T.sequence[elem]
        if isinstance(r, ir.Array):
            dims, elem_t = self.t.array_shape(r)
            h = self.hint(elem_t)
            for n in reversed(dims):
                h = T.array[h, n]
            return h
        if isinstance(r, ir.TypeRef) and r.kind in ("struct", "union", "enum"):
            return self.cls(r.name)
        raise Unsupported(str(t))

    # -- values -----------------------------------------------------------------------------
    def to_obj(self, t: ir.Type, v: object) -> object:
        r = self.t.resolve(t)
        if isinstance(r, ir.Primitive):
            if r.name == "char16":
                return ord(v)  # type: ignore[arg-type]
            return v
        if isinstance(r, (ir.String,)):
            return v
        if isinstance(r, ir.Sequence):
            return [self.to_obj(r.element, x) for x in v]  # type: ignore[union-attr]
        if isinstance(r, ir.Array):
            dims, elem = self.t.array_shape(r)
            return self._array_obj(elem, v, len(dims))
        d = self.model.get(r.name)  # type: ignore[union-attr]
        c = self.cls(d.scoped_name)  # type: ignore[union-attr]
        if isinstance(d, ir.Enum):
            return c(self.t.enum_maps(d)[0][v])  # type: ignore[index,operator]
        if isinstance(d, ir.Struct):
            kwargs = {}
            for mi, fname in zip(self.t.members(d), self.fields(c, d)):
                x = v.get(mi.member.name)  # type: ignore[union-attr]
                kwargs[fname] = None if x is None else self.to_obj(mi.member.type, x)
            return c(**kwargs)
        if isinstance(d, ir.Union):
            disc = v["discriminator"]  # type: ignore[index]
            case = self.t.union_case(d, self.t.disc_number(d, disc))
            rd = self.t.resolve(d.discriminator)
            disc_obj = self.to_obj(rd, disc) if isinstance(rd, ir.TypeRef) else disc
            value = self.to_obj(case.member.type, v["value"]) if case is not None else None  # type: ignore[index]
            return c(discriminator=disc_obj, value=value)
        raise Unsupported(str(t))

    def _array_obj(self, elem: ir.Type, v: object, depth: int) -> object:
        if depth == 1:
            if self.t.resolve(elem) in (ir.Primitive("octet"), ir.Primitive("uint8")):
                return bytes(v)  # type: ignore[arg-type]
            return [self.to_obj(elem, x) for x in v]  # type: ignore[union-attr]
        return [self._array_obj(elem, x, depth - 1) for x in v]  # type: ignore[union-attr]

    def from_obj(self, t: ir.Type, o: object) -> object:
        r = self.t.resolve(t)
        if isinstance(r, ir.Primitive):
            if r.name == "char16":
                return chr(o)  # type: ignore[arg-type]
            if r.name == "boolean":
                return bool(o)
            return o
        if isinstance(r, ir.String):
            return o
        if isinstance(r, ir.Sequence):
            return [self.from_obj(r.element, x) for x in o]  # type: ignore[union-attr]
        if isinstance(r, ir.Array):
            dims, elem = self.t.array_shape(r)
            return self._array_val(elem, o, len(dims))
        d = self.model.get(r.name)  # type: ignore[union-attr]
        if isinstance(d, ir.Enum):
            number = o.value if isinstance(o, IdlEnum) else o
            return self.t.enum_maps(d)[1].get(number, number)  # type: ignore[call-overload]
        if isinstance(d, ir.Struct):
            out = {}
            for mi, fname in zip(self.t.members(d), self.fields(type(o), d)):
                x = getattr(o, fname)
                out[mi.member.name] = None if x is None and mi.member.optional else self.from_obj(mi.member.type, x)
            return out
        if isinstance(d, ir.Union):
            assert isinstance(o, IdlUnion)
            disc = o.discriminator
            rd = self.t.resolve(d.discriminator)
            disc_v = self.from_obj(rd, disc) if isinstance(rd, ir.TypeRef) else disc
            case = self.t.union_case(d, self.t.disc_number(d, disc_v))
            out = {"discriminator": disc_v}
            if case is not None:
                out["value"] = self.from_obj(case.member.type, o.value)
            return out
        raise Unsupported(str(t))

    def fields(self, c: type, d: ir.Struct) -> list[str]:
        names = [f.name for f in dataclasses.fields(c)]
        if len(names) != len(self.t.members(d)):
            raise AssertionError(f"{c.__name__} has {len(names)} fields, {d.scoped_name} {len(self.t.members(d))} members")
        return names

    def _array_val(self, elem: ir.Type, o: object, depth: int) -> object:
        if depth == 1:
            return [self.from_obj(elem, x) for x in o]  # type: ignore[union-attr]
        return [self._array_val(elem, x, depth - 1) for x in o]  # type: ignore[union-attr]


__all__ = ["CycloneTypes", "Unsupported", "generated_classes"]
