"""The resolved model (IR): frozen dataclasses named after the OMG IDL 4.2 spec.

Types refer to declarations by scoped name (`TypeRef("rapid::Header", "struct")`), never
by object, so the IR has no cycles and no parent pointers. A RAPID `valuetype X : Message`
is a Struct with base `rapid::Message` and origin "valuetype": same wire layout.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from decimal import Decimal
from functools import cached_property
from typing import Callable, Literal

from rapidgen.diagnostics import SourceLoc

# The kinds, as the type checker sees them (dispatch on them is typed, never by a
# method name built from a string).
TypeKind = Literal["struct", "union", "enum", "bitmask", "bitset", "typedef", "native"]
DeclKind = Literal["struct", "union", "enum", "bitmask", "bitset", "typedef", "native", "const"]
Extensibility = Literal["final", "appendable", "mutable"]
AutoId = Literal["SEQUENTIAL", "HASH"]
Origin = Literal["struct", "valuetype"]

MEMBER_ID_MASK = 0x0FFFFFFF  # XTypes member ids are 28 bits
MAX_CHAIN = 1000  # typedef and inheritance chains followed (a guard: resolution refuses cycles)

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
    kind: TypeKind

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
Label = int | bool | str | EnumValue  # a union case label, or a discriminator value


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
    id: int | None = None  # the declared @id, if any
    default: ConstValue | None = None
    # The effective XTypes member id, resolved once: @id, else the hash of @hashid's text
    # or of the name (@hashid, @autoid(HASH) of the declaring type), else the previous
    # member's id + 1 (base members come first). 28 bits.
    member_id: int = 0


@dataclass(frozen=True, slots=True)
class Struct:
    name: str
    scoped_name: str
    loc: SourceLoc
    members: tuple[Member, ...]  # own members only; base members come first on the wire
    base: str | None = None
    annotations: tuple[Annotation, ...] = ()
    extensibility: Extensibility = "final"
    keys: tuple[str, ...] = ()  # full key paths, base keys first: ("hdr.srcName", "cmdId")
    origin: Origin = "struct"
    nested: bool = False
    autoid: AutoId = "SEQUENTIAL"  # of its own members (a base's members keep the base's)
    kind: Literal["struct"] = field(default="struct", init=False)


@dataclass(frozen=True, slots=True)
class UnionCase:
    labels: tuple[Label, ...]
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
    extensibility: Extensibility = "final"
    discriminator_key: bool = False
    nested: bool = False
    autoid: AutoId = "SEQUENTIAL"
    # The union's default value, resolved once: the discriminator's type default
    # (@default_literal enumerator, 0, FALSE, NUL) and the case it selects: the case
    # labelled with it, else the `default:` case, else none (no member).
    default_discriminator: Label = 0
    default_case: int | None = None  # index into cases
    kind: Literal["union"] = field(default="union", init=False)

    @property
    def default_member(self) -> Member | None:
        return self.cases[self.default_case].member if self.default_case is not None else None


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
    extensibility: Extensibility = "final"
    # The enumerator a value defaults to, resolved once: the @default_literal one, else
    # the first; default_declared says whether @default_literal chose it.
    default: str = ""
    default_declared: bool = False
    kind: Literal["enum"] = field(default="enum", init=False)

    @property
    def default_enumerator(self) -> Enumerator | None:
        return next((e for e in self.enumerators if e.name == self.default), None)


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
    kind: Literal["bitmask"] = field(default="bitmask", init=False)


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
    kind: Literal["bitset"] = field(default="bitset", init=False)


@dataclass(frozen=True, slots=True)
class Typedef:
    name: str
    scoped_name: str
    loc: SourceLoc
    type: Type
    annotations: tuple[Annotation, ...] = ()
    kind: Literal["typedef"] = field(default="typedef", init=False)


@dataclass(frozen=True, slots=True)
class Const:
    name: str
    scoped_name: str
    loc: SourceLoc
    type: Type
    value: ConstValue
    annotations: tuple[Annotation, ...] = ()
    kind: Literal["const"] = field(default="const", init=False)


@dataclass(frozen=True, slots=True)
class Native:
    name: str
    scoped_name: str
    loc: SourceLoc
    annotations: tuple[Annotation, ...] = ()
    kind: Literal["native"] = field(default="native", init=False)


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
        """Follow typedefs to the underlying type (the one unalias: see `unalias`)."""
        if type(t) is not TypeRef or t.kind != "typedef":  # most types: nothing to follow
            return t
        return unalias(t, self.by_name.get)

    @cached_property
    def _flat(self) -> dict[str, tuple[Member, ...]]:
        return {}

    @cached_property
    def _memos(self) -> dict[str, dict]:
        return {}

    def memo(self, name: str) -> dict:
        """A dict kept with the model for a query's results (the model never changes)."""
        return self._memos.setdefault(name, {})

    def all_members(self, struct: Struct) -> tuple[Member, ...]:
        """Members in wire order: base members first (the one flattening: see `flatten`)."""
        got = self._flat.get(struct.scoped_name)
        if got is None:
            got = self._flat[struct.scoped_name] = flatten(struct, self.by_name.get)
        return got

    def key_path(self, struct: Struct, path: str) -> tuple[tuple[Struct, Member], ...] | None:
        """A key path ('hdr.srcName') as the (struct, member) steps it takes from `struct`;
        None when a step names no member."""
        steps: list[tuple[Struct, Member]] = []
        current: Struct | None = struct
        for part in path.split("."):
            member = next((m for m in self.all_members(current) if m.name == part), None) if current else None
            if current is None or member is None:
                return None
            steps.append((current, member))
            t = self.resolve_alias(member.type)
            d = self.get(t.name) if isinstance(t, TypeRef) else None
            current = d if isinstance(d, Struct) else None
        return tuple(steps)

    def lineage(self, d: Struct | Bitset) -> tuple[Struct | Bitset, ...]:
        """A struct's (or bitset's) base chain, the root first and `d` last."""
        return lineage(d, self.by_name.get)

    def all_fields(self, bitset: Bitset) -> tuple[Bitfield, ...]:
        """A bitset's fields, its bases' first."""
        return tuple(f for b in lineage(bitset, self.by_name.get) if isinstance(b, Bitset) for f in b.fields)


# -- queries, also used by resolution (before there is a Model) -------------------------
Lookup = Callable[[str], "Declaration | None"]


def unalias(t: Type, get: Lookup) -> Type:
    """Follow a typedef chain to the type it names; an unknown name stops it."""
    for _ in range(MAX_CHAIN):
        if not (isinstance(t, TypeRef) and t.kind == "typedef"):
            break
        decl = get(t.name)
        if not isinstance(decl, Typedef):
            break
        t = decl.type
    return t


def lineage(d: Struct | Bitset, get: Lookup) -> tuple[Struct | Bitset, ...]:
    """`d` and its bases, the root first; a base of another kind (or unknown) ends it."""
    chain: list[Struct | Bitset] = [d]
    while len(chain) < MAX_CHAIN:
        base = get(chain[-1].base) if chain[-1].base else None
        if type(base) is not type(d):
            break
        chain.append(base)
    return tuple(reversed(chain))


def label_key(label: object) -> tuple[bool, object]:
    """Comparable key of a union label or discriminator value (enumerators by value;
    True and 1 stay apart)."""
    if isinstance(label, EnumValue):
        return (False, label.value)
    return (type(label) is bool, label)


def flatten(struct: Struct, get: Lookup) -> tuple[Member, ...]:
    """A struct's members in wire order: base members first."""
    return tuple(m for s in lineage(struct, get) if isinstance(s, Struct) for m in s.members)
