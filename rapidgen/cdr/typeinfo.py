"""What the XCDR encoder and decoder need to know about the model's types.

`CdrTypes(model)` answers, with caches: the type behind a typedef chain, primitive
formats, which element types count as primitive for XCDR2 (no DHEADER), the member ids
of a struct, the wire size of enums and bitmasks, and a lower bound of any type's
encoded size (the decoder checks counts against it before it allocates).

Pure model code: no DDS library, no I/O. See docs/cdr-and-vectors.md.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass
from decimal import Decimal

from rapidgen.model import ir


class CdrError(ValueError):
    """A value that cannot be encoded, or bytes that do not decode.

    `offset` is the byte position in the buffer (counted from the start of the
    encapsulation header when there is one), `path` where in the value it happened
    (`hdr.srcName`, `arguments[3].value`).
    """

    def __init__(self, message: str, offset: int | None = None, path: str = "") -> None:
        self.message = message
        self.offset = offset
        self.path = path
        super().__init__(self._text())

    def _text(self) -> str:
        where = f" at offset {self.offset}" if self.offset is not None else ""
        inside = f" (in {self.path})" if self.path else ""
        return f"{self.message}{where}{inside}"

    def within(self, step: str) -> "CdrError":
        """Prefix the path with one more step (a member name or an index)."""
        joint = "." if self.path and not self.path.startswith("[") else ""
        self.path = step + joint + self.path
        self.args = (self._text(),)
        return self


# name -> (struct format, size); char8, char16, boolean and float128 are handled apart.
PRIMITIVES: dict[str, tuple[str, int]] = {
    "int8": ("b", 1), "uint8": ("B", 1), "octet": ("B", 1), "int16": ("h", 2), "uint16": ("H", 2),
    "int32": ("i", 4), "uint32": ("I", 4), "int64": ("q", 8), "uint64": ("Q", 8),
    "float32": ("f", 4), "float64": ("d", 8), "float128": ("", 16),
    "char8": ("B", 1), "char16": ("H", 2), "boolean": ("B", 1),
}

MAX_DEPTH = 100  # nesting of aggregates and collections, in values and in bytes
MAX_EMPTY_ELEMENTS = 1 << 16  # count limit for collections whose elements may take 0 bytes
# The decoder's budget of values (elements, aggregates, defaults of absent members) for
# one input: MAX_VALUES_BASE + VALUES_PER_BYTE x its length. Real data makes about one
# value per byte or less; defaults and empty elements are what make more from nothing.
MAX_VALUES_BASE = 1 << 16
VALUES_PER_BYTE = 16

_STRUCT_CACHE: dict[str, struct.Struct] = {}


def packer(fmt: str) -> struct.Struct:
    """A compiled struct format; the fixed ones are kept, counted ones ("<12i") are not."""
    s = _STRUCT_CACHE.get(fmt)
    if s is None:
        s = struct.Struct(fmt)
        if len(fmt) <= 3:
            _STRUCT_CACHE[fmt] = s
    return s


@dataclass(frozen=True, slots=True)
class MemberInfo:
    member: ir.Member
    id: int
    must_understand: bool  # key members and @must_understand ones


def int_size(bit_bound: int) -> int:
    """Bytes holding a @bit_bound value: 1..8 -> 1, 9..16 -> 2, 17..32 -> 4, 33..64 -> 8."""
    for size, bits in ((1, 8), (2, 16), (4, 32), (8, 64)):
        if bit_bound <= bits:
            return size
    return 8


label_key = ir.label_key


def _ann(annotations: tuple[ir.Annotation, ...], name: str) -> dict[str, object] | None:
    for a in annotations:
        if a.name == name:
            return dict(a.params)
    return None


class CdrTypes:
    """Type questions for the codec, answered from the Model and cached."""

    def __init__(self, model: ir.Model) -> None:
        self.model = model
        self._resolved: dict[ir.Type, ir.Type] = {}
        self._members: dict[str, tuple[MemberInfo, ...]] = {}
        self._min: dict[tuple[ir.Type, int], int] = {}
        self._default_counts: dict[ir.Type, int] = {}
        self._enums: dict[str, tuple[dict[str, int], dict[int, str]]] = {}
        self._unions: dict[str, tuple[dict[object, ir.UnionCase], ir.UnionCase | None]] = {}

    # -- resolution -------------------------------------------------------------------
    def resolve(self, t: ir.Type) -> ir.Type:
        """Follow typedefs; raise CdrError for names the model does not hold."""
        try:
            return self._resolved[t]
        except KeyError:
            pass
        r = self.model.resolve_alias(t)
        if isinstance(r, ir.TypeRef) and r.kind == "typedef":
            raise CdrError(f"typedef '{r.name}' does not resolve")
        self._resolved[t] = r
        return r

    def decl(self, t: ir.TypeRef) -> ir.Declaration:
        d = self.model.get(t.name)
        if d is None:
            raise CdrError(f"unknown type '{t.name}'")
        return d

    def type_of(self, spec: str | ir.Type) -> ir.Type:
        """A type given by scoped name (`rapid::Command`) or as a type expression."""
        if not isinstance(spec, str):
            return self.resolve(spec)
        d = self.model.get(spec)
        if d is None:
            raise CdrError(f"unknown type '{spec}'")
        if isinstance(d, ir.Typedef):
            return self.resolve(d.type)
        if isinstance(d, (ir.Struct, ir.Union, ir.Enum, ir.Bitmask, ir.Bitset)):
            return ir.TypeRef(d.scoped_name, d.kind)
        raise CdrError(f"'{spec}' is {d.kind}, not a type that can be encoded")

    def extensibility(self, t: ir.Type) -> str:
        r = self.resolve(t)
        if isinstance(r, ir.TypeRef) and r.kind in ("struct", "union"):
            d = self.decl(r)
            return getattr(d, "extensibility", "final")
        return "final"

    # -- arrays: a typedef'd array inside an array is one multi-dimensional array -------
    def array_shape(self, t: ir.Array) -> tuple[tuple[int, ...], ir.Type]:
        dims = list(t.dims)
        elem = self.resolve(t.element)
        guard = 0
        while isinstance(elem, ir.Array) and guard < 100:
            dims.extend(elem.dims)
            elem = self.resolve(elem.element)
            guard += 1
        return tuple(dims), elem

    # -- classification -----------------------------------------------------------------
    def is_primitive(self, t: ir.Type) -> bool:
        """Primitive for XCDR2 purposes: collections of these carry no DHEADER.

        Enums, bitmasks, strings and everything else are not (as in Cyclone DDS)."""
        return isinstance(self.resolve(t), ir.Primitive)

    def enum_size(self, e: ir.Enum) -> int:
        return int_size(e.bit_bound)

    def bitmask_size(self, b: ir.Bitmask) -> int:
        return int_size(b.bit_bound)

    def bitset_fields(self, b: ir.Bitset) -> tuple[ir.Bitfield, ...]:
        return self.model.all_fields(b)

    def bitset_size(self, b: ir.Bitset) -> int:
        return int_size(max(1, sum(f.width for f in self.bitset_fields(b))))

    # -- members --------------------------------------------------------------------------
    def members(self, s: ir.Struct) -> tuple[MemberInfo, ...]:
        """Members in wire order (base first) with their XTypes member ids (resolved in
        the model)."""
        cached = self._members.get(s.scoped_name)
        if cached is not None:
            return cached
        out: list[MemberInfo] = []
        for m in self.model.all_members(s):
            mu = _ann(m.annotations, "must_understand")
            out.append(MemberInfo(m, m.member_id, m.key or bool(mu and mu.get("value", True))))
        result = tuple(out)
        self._members[s.scoped_name] = result
        return result

    # -- enums and unions ---------------------------------------------------------------------
    def enum_maps(self, e: ir.Enum) -> tuple[dict[str, int], dict[int, str]]:
        got = self._enums.get(e.scoped_name)
        if got is None:
            by_name = {x.name: x.value for x in e.enumerators}
            by_value: dict[int, str] = {}
            for x in e.enumerators:
                by_value.setdefault(x.value, x.name)
            got = self._enums[e.scoped_name] = (by_name, by_value)
        return got

    def union_cases(self, u: ir.Union) -> tuple[dict[object, ir.UnionCase], ir.UnionCase | None]:
        """Label (enumerators as their integer value) -> case, and the default case."""
        got = self._unions.get(u.scoped_name)
        if got is None:
            table: dict[object, ir.UnionCase] = {}
            default = None
            for case in u.cases:
                if case.is_default:
                    default = case
                for label in case.labels:
                    table.setdefault(label_key(label), case)
            got = self._unions[u.scoped_name] = (table, default)
        return got

    def union_case(self, u: ir.Union, disc: object) -> ir.UnionCase | None:
        """The case a discriminator value selects (enums as integers); None: no member."""
        table, default = self.union_cases(u)
        case = table.get(label_key(disc))
        return case if case is not None else default

    # -- lower bound of the encoded size ---------------------------------------------------
    def min_size(self, t: ir.Type, version: int) -> int:
        """Fewest bytes any value of `t` takes (ignoring alignment padding)."""
        key = (t, version)
        got = self._min.get(key)
        if got is not None:
            return got
        self._min[key] = 0  # a recursive type reaches itself: count it as 0 there
        size = self._min_size(self.resolve(t), version)
        self._min[key] = size
        return size

    def _min_size(self, r: ir.Type, v: int) -> int:
        if isinstance(r, ir.Primitive):
            return PRIMITIVES[r.name][1]
        if isinstance(r, ir.String):
            return 4 if r.wide else 5  # length (+ the NUL of a narrow string)
        if isinstance(r, (ir.Sequence, ir.Map)):
            elem = r.element if isinstance(r, ir.Sequence) else r.key
            dheader = v == 2 and not (self.is_primitive(elem) and
                                      (isinstance(r, ir.Sequence) or self.is_primitive(r.value)))
            return 4 + (4 if dheader else 0)
        if isinstance(r, ir.Array):
            dims, elem = self.array_shape(r)
            n = 1
            for size in dims:
                n *= size
            return n * self.min_size(elem, v) + (4 if v == 2 and not self.is_primitive(elem) else 0)
        if isinstance(r, ir.Fixed):
            return (r.digits + 2) // 2
        if isinstance(r, ir.TypeRef):
            d = self.decl(r)
            if isinstance(d, ir.Enum):
                return self.enum_size(d)
            if isinstance(d, ir.Bitmask):
                return self.bitmask_size(d)
            if isinstance(d, ir.Bitset):
                return self.bitset_size(d)
            if isinstance(d, ir.Struct):
                ext = d.extensibility
                if ext == "mutable":
                    return 4  # DHEADER (XCDR2) or the list-end sentinel (XCDR1)
                if v == 2 and ext == "appendable":
                    return 4  # DHEADER 0: an older writer's type may end before any member
                total = 0
                for mi in self.members(d):
                    if mi.member.optional:
                        total += 1 if v == 2 else 4
                    else:
                        total += self.min_size(mi.member.type, v)
                return total
            if isinstance(d, ir.Union):
                return self.min_size(d.discriminator, v) + (4 if v == 2 and d.extensibility != "final" else 0)
        return 0

    # -- default values (members an appendable or mutable encoding leaves out) -------------------
    def default_count(self, t: ir.Type, depth: int = 0) -> int:
        """How many values default_value(t) builds (lists and dicts included), without
        building them: the decoder charges its budget before filling in an absent member."""
        got = self._default_counts.get(t)
        if got is not None:
            return got
        if depth > MAX_DEPTH:
            raise CdrError("type nests too deeply for a default value")
        r = self.resolve(t)
        n = 1
        if isinstance(r, ir.Array):
            dims, elem = self.array_shape(r)
            total, lists = 1, 0
            for size in dims:
                lists += total
                total *= size
            n = lists + total * self.default_count(elem, depth + 1)
        elif isinstance(r, ir.TypeRef):
            d = self.decl(r)
            if isinstance(d, ir.Struct):
                n += sum(1 if mi.member.optional else self.default_count(mi.member.type, depth + 1)
                         for mi in self.members(d))
            elif isinstance(d, ir.Union):
                n += 2  # the discriminator and the value of the member its default selects
                member = d.default_member
                n += self.default_count(member.type, depth + 1) if member is not None else 0
            elif isinstance(d, ir.Bitset):
                n += len(self.bitset_fields(d))
        self._default_counts[t] = n
        return n

    def default_value(self, t: ir.Type, depth: int = 0) -> object:
        if depth > MAX_DEPTH:
            raise CdrError("type nests too deeply for a default value")
        r = self.resolve(t)
        if isinstance(r, ir.Primitive):
            if r.name == "boolean":
                return False
            if r.name in ("char8", "char16"):
                return "\0"
            return 0.0 if r.name in ir.FLOAT_TYPES else 0
        if isinstance(r, ir.String):
            return ""
        if isinstance(r, (ir.Sequence, ir.Map)):
            return []
        if isinstance(r, ir.Array):
            dims, elem = self.array_shape(r)
            return self._filled(dims, lambda: self.default_value(elem, depth + 1))
        if isinstance(r, ir.Fixed):
            return format_fixed(0, r.scale)
        if isinstance(r, ir.TypeRef):
            d = self.decl(r)
            if isinstance(d, ir.Enum):
                return d.default or 0  # the @default_literal enumerator, else the first
            if isinstance(d, ir.Bitmask):
                return 0
            if isinstance(d, ir.Bitset):
                return {f.name: (False if f.type.name == "boolean" else 0) for f in self.bitset_fields(d) if f.name}
            if isinstance(d, ir.Struct):
                return {mi.member.name: (None if mi.member.optional else self.default_value(mi.member.type, depth + 1))
                        for mi in self.members(d)}
            if isinstance(d, ir.Union):
                return self.default_union(d, depth)
        raise CdrError(f"no default value for type '{t}'")

    def default_union(self, d: ir.Union, depth: int = 0) -> dict[str, object]:
        """The union's default value, as the model resolved it (the bindings' too)."""
        out: dict[str, object] = {"discriminator": label_value(d.default_discriminator)}
        member = d.default_member
        if member is not None:
            out["value"] = self.default_value(member.type, depth + 1)
        return out

    def disc_number(self, d: ir.Union, disc: object) -> object:
        """A discriminator in value form (enumerator name) as the label it compares with."""
        r = self.resolve(d.discriminator)
        if isinstance(r, ir.TypeRef) and isinstance(disc, str):
            e = self.decl(r)
            if isinstance(e, ir.Enum):
                by_name, _ = self.enum_maps(e)
                if disc in by_name:
                    return by_name[disc]
        return disc

    @staticmethod
    def _filled(dims: tuple[int, ...], make) -> list:
        if len(dims) == 1:
            return [make() for _ in range(dims[0])]
        return [CdrTypes._filled(dims[1:], make) for _ in range(dims[0])]


def label_value(label: object) -> object:
    """A union label in value form: enumerators by name."""
    return label.name if isinstance(label, ir.EnumValue) else label


def format_fixed(number: Decimal | int, scale: int) -> str:
    """A fixed-point value as the decimal string of the value form ("-12.50" for scale 2)."""
    q = Decimal(number).quantize(Decimal(1).scaleb(-scale))
    text = format(q, "f")
    return text[1:] if text.startswith("-") and q == 0 else text
