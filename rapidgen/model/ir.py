"""The resolved model (IR): frozen dataclasses named after the OMG IDL 4.2 spec.

Types refer to declarations by scoped name (`TypeRef("rapid::Header", "struct")`), never
by object, so the IR has no cycles and no parent pointers. A RAPID `valuetype X : Message`
is a Struct with base `rapid::Message` and origin "valuetype": same wire layout.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from decimal import Decimal
from functools import cached_property

from rapidgen.diagnostics import SourceLoc

INTEGER_RANGES: dict[str, tuple[int, int]] = {
    "int8": (-2**7, 2**7 - 1), "uint8": (0, 2**8 - 1),
    "int16": (-2**15, 2**15 - 1), "uint16": (0, 2**16 - 1),
    "int32": (-2**31, 2**31 - 1), "uint32": (0, 2**32 - 1),
    "int64": (-2**63, 2**63 - 1), "uint64": (0, 2**64 - 1),
    "octet": (0, 255),
}
FLOAT_TYPES = frozenset({"float32", "float64", "float128"})
CHAR_TYPES = frozenset({"char8", "char16"})

# IDL spelling of each primitive, for messages and `rapidgen ir` output.
IDL_SPELLING = {
    "int8": "int8", "uint8": "uint8", "int16": "short", "uint16": "unsigned short",
    "int32": "long", "uint32": "unsigned long", "int64": "long long",
    "uint64": "unsigned long long", "float32": "float", "float64": "double",
    "float128": "long double", "char8": "char", "char16": "wchar", "boolean": "boolean",
    "octet": "octet",
}


@dataclass(frozen=True, slots=True)
class Annotation:
    name: str
    params: tuple[tuple[str, object], ...]
    loc: SourceLoc


# -- type expressions ----------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Primitive:
    name: str  # int8..uint64, float32/64/128, char8, char16, boolean, octet

    def __str__(self) -> str:
        return IDL_SPELLING[self.name]


@dataclass(frozen=True, slots=True)
class String:
    bound: int | None
    wide: bool = False

    def __str__(self) -> str:
        word = "wstring" if self.wide else "string"
        return f"{word}<{self.bound}>" if self.bound else word


@dataclass(frozen=True, slots=True)
class Sequence:
    element: "Type"
    bound: int | None

    def __str__(self) -> str:
        return f"sequence<{self.element}, {self.bound}>" if self.bound else f"sequence<{self.element}>"


@dataclass(frozen=True, slots=True)
class Array:
    element: "Type"
    dims: tuple[int, ...]

    def __str__(self) -> str:
        return f"{self.element}" + "".join(f"[{d}]" for d in self.dims)


@dataclass(frozen=True, slots=True)
class Map:
    key: "Type"
    value: "Type"
    bound: int | None

    def __str__(self) -> str:
        inner = f"{self.key}, {self.value}" + (f", {self.bound}" if self.bound else "")
        return f"map<{inner}>"


@dataclass(frozen=True, slots=True)
class Fixed:
    digits: int
    scale: int

    def __str__(self) -> str:
        return f"fixed<{self.digits}, {self.scale}>"


@dataclass(frozen=True, slots=True)
class TypeRef:
    name: str  # scoped name, a::b::C
    kind: str  # struct | union | enum | bitmask | bitset | typedef | native

    def __str__(self) -> str:
        return self.name


Type = Primitive | String | Sequence | Array | Map | Fixed | TypeRef


@dataclass(frozen=True, slots=True)
class EnumValue:
    """A constant whose value is an enumerator."""

    enum: str  # scoped name of the enum
    name: str  # enumerator name
    value: int

    def __str__(self) -> str:
        return self.name


ConstValue = int | float | Decimal | str | bool | EnumValue


# -- declarations ----------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Member:
    name: str
    type: Type
    loc: SourceLoc
    annotations: tuple[Annotation, ...] = ()
    key: bool = False
    optional: bool = False
    external: bool = False
    id: int | None = None
    default: ConstValue | None = None


@dataclass(frozen=True, slots=True)
class Struct:
    name: str
    scoped_name: str
    loc: SourceLoc
    members: tuple[Member, ...]  # own members only; base members come first on the wire
    base: str | None = None
    annotations: tuple[Annotation, ...] = ()
    extensibility: str = "final"
    keys: tuple[str, ...] = ()  # full key paths, base keys first: ("hdr.srcName", "cmdId")
    origin: str = "struct"  # struct | valuetype
    nested: bool = False
    kind: str = field(default="struct", init=False)


@dataclass(frozen=True, slots=True)
class UnionCase:
    labels: tuple[int | bool | str | EnumValue, ...]
    is_default: bool
    member: Member


@dataclass(frozen=True, slots=True)
class Union:
    name: str
    scoped_name: str
    loc: SourceLoc
    discriminator: Type
    cases: tuple[UnionCase, ...]
    annotations: tuple[Annotation, ...] = ()
    extensibility: str = "final"
    discriminator_key: bool = False
    nested: bool = False
    kind: str = field(default="union", init=False)


@dataclass(frozen=True, slots=True)
class Enumerator:
    name: str
    value: int
    loc: SourceLoc
    annotations: tuple[Annotation, ...] = ()


@dataclass(frozen=True, slots=True)
class Enum:
    name: str
    scoped_name: str
    loc: SourceLoc
    enumerators: tuple[Enumerator, ...]
    bit_bound: int = 32
    annotations: tuple[Annotation, ...] = ()
    extensibility: str = "final"
    kind: str = field(default="enum", init=False)


@dataclass(frozen=True, slots=True)
class BitValue:
    name: str
    position: int
    loc: SourceLoc
    annotations: tuple[Annotation, ...] = ()


@dataclass(frozen=True, slots=True)
class Bitmask:
    name: str
    scoped_name: str
    loc: SourceLoc
    values: tuple[BitValue, ...]
    bit_bound: int = 32
    annotations: tuple[Annotation, ...] = ()
    kind: str = field(default="bitmask", init=False)


@dataclass(frozen=True, slots=True)
class Bitfield:
    name: str | None  # None: anonymous padding bits
    width: int
    type: Primitive
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class Bitset:
    name: str
    scoped_name: str
    loc: SourceLoc
    fields: tuple[Bitfield, ...]
    base: str | None = None
    annotations: tuple[Annotation, ...] = ()
    kind: str = field(default="bitset", init=False)


@dataclass(frozen=True, slots=True)
class Typedef:
    name: str
    scoped_name: str
    loc: SourceLoc
    type: Type
    annotations: tuple[Annotation, ...] = ()
    kind: str = field(default="typedef", init=False)


@dataclass(frozen=True, slots=True)
class Const:
    name: str
    scoped_name: str
    loc: SourceLoc
    type: Type
    value: ConstValue
    annotations: tuple[Annotation, ...] = ()
    kind: str = field(default="const", init=False)


@dataclass(frozen=True, slots=True)
class Native:
    name: str
    scoped_name: str
    loc: SourceLoc
    annotations: tuple[Annotation, ...] = ()
    kind: str = field(default="native", init=False)


@dataclass(frozen=True, slots=True)
class Module:
    name: str
    scoped_name: str
    loc: SourceLoc  # where it is first opened


Declaration = Struct | Union | Enum | Bitmask | Bitset | Typedef | Const | Native


@dataclass(frozen=True)
class Model:
    """Every declaration in dependency order (a declaration follows what it needs)."""

    modules: tuple[Module, ...]
    declarations: tuple[Declaration, ...]
    files: tuple[str, ...] = ()

    @cached_property
    def by_name(self) -> dict[str, Declaration]:
        return {d.scoped_name: d for d in self.declarations}

    def get(self, scoped_name: str) -> Declaration | None:
        return self.by_name.get(scoped_name.lstrip(":"))

    def resolve_alias(self, t: Type) -> Type:
        """Follow typedefs to the underlying type."""
        seen = 0
        while isinstance(t, TypeRef) and t.kind == "typedef" and seen < 1000:
            decl = self.by_name.get(t.name)
            if not isinstance(decl, Typedef):
                break
            t = decl.type
            seen += 1
        return t

    def all_members(self, struct: Struct) -> tuple[Member, ...]:
        """Members in wire order: base members first."""
        chain: list[Struct] = []
        cur: Struct | None = struct
        while cur is not None and len(chain) < 1000:
            chain.append(cur)
            base = self.by_name.get(cur.base) if cur.base else None
            cur = base if isinstance(base, Struct) else None
        return tuple(m for s in reversed(chain) for m in s.members)
