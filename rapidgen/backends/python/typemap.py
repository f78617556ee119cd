"""IDL types as `cyclonedds.idl` annotations, and the default value of each type.

A `TypeMapper` turns IR type expressions into Python source text for one generated
module; it asks its context for the local name of every declaration it mentions (the
context records the import) and notes every name the text evaluates, so the view can
keep member names from shadowing them inside a class body.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import Decimal
from typing import Protocol

from rapidgen.backends.escape import py_str
from rapidgen.diagnostics import SourceLoc
from rapidgen.model import ir

PRIMITIVES = {
    "int8": "types.int8", "uint8": "types.uint8", "int16": "types.int16", "uint16": "types.uint16",
    "int32": "types.int32", "uint32": "types.uint32", "int64": "types.int64", "uint64": "types.uint64",
    "float32": "types.float32", "float64": "types.float64", "boolean": "bool", "octet": "types.byte",
    "char8": "types.char",
}
# What cyclonedds 11 cannot encode; the python target refuses them instead of guessing.
UNSUPPORTED_PRIMITIVES = {"float128": "long double", "char16": "wchar"}
# types.sequence[T, N] refuses N > 65535 in cyclonedds 11.0.1; bigger bounds go through
# the generated package's _support.sequence(T, N) (same annotation, built directly).
MAX_SUBSCRIPT_BOUND = 65535


class Unsupported(Exception):
    def __init__(self, message: str, loc: SourceLoc | None = None) -> None:
        super().__init__(message)
        self.loc = loc


class Context(Protocol):
    def ref(self, scoped_name: str) -> tuple[str, bool]:
        """(local Python name, declared later in this module) of a declaration."""

    def enumerator(self, enum_scoped: str, idl_name: str) -> str:
        """Python name of an enumerator."""

    def support(self) -> str:
        """Local name of the package's _support module (imports it)."""


@dataclass(frozen=True)
class Value:
    expr: str  # a Python expression giving a fresh default value
    mutable: bool  # needs a default_factory
    forward: bool = False  # names a class defined later in the module


def default_refs(model: ir.Model, t: ir.Type, depth: int = 0) -> list[str]:
    """Declarations the default value of a type names (its class, an enum, a union branch)."""
    if depth > 64:
        return []
    t = model.resolve_alias(t)
    if isinstance(t, ir.Array):
        return default_refs(model, t.element, depth + 1)
    if not isinstance(t, ir.TypeRef):
        return []
    d = model.get(t.name)
    if isinstance(d, ir.Union):
        label, member = d.default_discriminator, d.default_member
        out = [d.scoped_name] + ([label.enum] if isinstance(label, ir.EnumValue) else [])
        return out + (default_refs(model, member.type, depth + 1) if member else [])
    return [t.name] if d is not None else []


class TypeMapper:
    def __init__(self, model: ir.Model, ctx: Context) -> None:
        self.model = model
        self.ctx = ctx

    # -- annotations -------------------------------------------------------------------
    def annotation(self, t: ir.Type, used: set[str], loc: SourceLoc) -> str:
        if isinstance(t, ir.Primitive):
            if t.name in UNSUPPORTED_PRIMITIVES:
                raise Unsupported(f"{UNSUPPORTED_PRIMITIVES[t.name]} is not supported by the python target "
                                  "(cyclonedds cannot encode it)", loc)
            text = PRIMITIVES[t.name]
            used.add(text.split(".")[0])
            return text
        if isinstance(t, ir.String):
            if t.wide:
                raise Unsupported("wstring is not supported by the python target (cyclonedds cannot encode it)", loc)
            if t.bound:
                used.add("types")
                return f"types.bounded_str[{t.bound}]"
            used.add("str")
            return "str"
        if isinstance(t, ir.Sequence):
            inner = self.annotation(t.element, used, loc)
            if t.bound is None:
                used.add("types")
                return f"types.sequence[{inner}]"
            if t.bound > MAX_SUBSCRIPT_BOUND:
                support = self.ctx.support()
                used.add(support)
                return f"{support}.sequence({inner}, {t.bound})"
            used.add("types")
            return f"types.sequence[{inner}, {t.bound}]"
        if isinstance(t, ir.Array):
            text = self.annotation(t.element, used, loc)
            used.add("types")
            for dim in reversed(t.dims):
                text = f"types.array[{text}, {dim}]"
            return text
        if isinstance(t, ir.Map):
            raise Unsupported("maps are not supported by the python target (cyclonedds 11 encodes them "
                              "but cannot describe them to DDS, so no topic could use the type)", loc)
        if isinstance(t, ir.Fixed):
            raise Unsupported("fixed-point types are not supported by the python target "
                              "(cyclonedds cannot encode them)", loc)
        if isinstance(t, ir.TypeRef):
            d = self.model.get(t.name)
            if isinstance(d, (ir.Bitset, ir.Native)):
                raise Unsupported(f"{d.kind} '{t.name}' is not supported by the python target "
                                  "(cyclonedds cannot encode it)", loc)
            name, forward = self.ctx.ref(t.name)
            if forward:
                return py_str(name)  # resolved by cyclonedds in this module once it is loaded
            used.add(name)
            return name
        raise Unsupported(f"type '{t}' is not supported by the python target", loc)

    def discriminator(self, t: ir.Type, used: set[str], loc: SourceLoc) -> str:
        return self.annotation(self.model.resolve_alias(t), used, loc)

    # -- values ------------------------------------------------------------------------
    def value(self, t: ir.Type, used: set[str], depth: int = 0) -> Value:
        """The default value of a type (zero, empty, first enumerator, default-built class)."""
        if isinstance(t, ir.Primitive):
            return Value({"float32": "0.0", "float64": "0.0", "boolean": "False",
                          "char8": py_str("\x00")}.get(t.name, "0"), False)
        if isinstance(t, ir.String):
            return Value('""', False)
        if isinstance(t, ir.Sequence):
            return Value("[]", True)
        if isinstance(t, ir.Array):
            inner = self.value(t.element, used, depth + 1)
            expr, mutable = inner.expr, inner.mutable
            for dim in reversed(t.dims):
                if mutable:
                    used.add("range")
                    expr = f"[{expr} for _ in range({dim})]"
                else:
                    expr = f"[{expr}] * {dim}"
                mutable = True
            return Value(expr, True, inner.forward)
        if isinstance(t, ir.TypeRef):
            d = self.model.get(t.name)
            if isinstance(d, ir.Typedef) and depth < 64:
                return self.value(self.model.resolve_alias(t), used, depth + 1)
            name, forward = self.ctx.ref(t.name)
            used.add(name)
            if isinstance(d, ir.Enum):
                return Value(f"{name}.{self.ctx.enumerator(d.scoped_name, d.default)}", False, forward)
            if isinstance(d, ir.Union):
                label, member = d.default_discriminator, d.default_member
                inner = self.value(member.type, used, depth + 1) if member else Value("None", False)
                return Value(f"{name}(discriminator={self.literal(label, used)}, value={inner.expr})", True,
                             forward or inner.forward)
            return Value(f"{name}()", True, forward)
        return Value("None", False)

    def field_default(self, t: ir.Type, used: set[str], *, optional: bool = False,
                      default: ir.ConstValue | None = None) -> str:
        """What follows `=` for a dataclass field of this type."""
        if optional:
            return "None"
        if default is not None:
            return self.literal(default, used)
        inner: set[str] = set()  # names the value evaluates; a lambda defers them to call time
        v = self.value(t, inner)
        if not v.mutable:
            used |= inner
            return v.expr
        used.add("field")
        if v.expr == "[]":
            used.add("list")
            return "field(default_factory=list)"
        if v.expr.endswith("()") and v.expr[:-2].isidentifier() and not v.forward:
            used |= inner
            return f"field(default_factory={v.expr[:-2]})"
        return f"field(default_factory=lambda: {v.expr})"

    # -- constants ---------------------------------------------------------------------
    def literal(self, value: object, used: set[str]) -> str:
        if isinstance(value, ir.EnumValue):
            name, _ = self.ctx.ref(value.enum)
            used.add(name)
            return f"{name}.{self.ctx.enumerator(value.enum, value.name)}"
        if isinstance(value, bool):
            return "True" if value else "False"
        if isinstance(value, int):
            return str(value)
        if isinstance(value, float):
            if math.isnan(value) or math.isinf(value):
                used.add("float")
                return f'float("{value}")'
            return repr(value)
        if isinstance(value, Decimal):
            used.add("Decimal")
            return f"Decimal({py_str(str(value))})"
        if isinstance(value, str):
            return py_str(value)
        if value is None:
            return "None"
        raise Unsupported(f"constant value {value!r} is not supported by the python target")
