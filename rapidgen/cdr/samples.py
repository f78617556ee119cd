"""Deterministic sample values of every struct and union in a Model (the golden vectors).

`samples(model)` returns, for each struct and union (sorted by scoped name), named
variants in the value form of `rapidgen.cdr`:

- `min`: the default value: empty sequences and strings, zeros, first enumerators, the
  first union branch.
- `max`: integers at their maximum, floats at large and tiny finite extremes, strings at
  their bound in non-ASCII UTF-8 (1- to 4-byte characters), small-bounded sequences at
  their bound (others with a few elements), last enumerators, union branches rotating.
- `low`: integers at their minimum, floats negative extremes, -0.0 and the smallest
  subnormal, strings at their bound in ASCII, one element per sequence.
- `mixed`: pseudo-random values from a fixed seed (the type's name): varied lengths and
  contents, exactly representable floats.
- per union branch: unions get `branch-<LABEL>` and `branch-<LABEL>-low` for every
  label; structs that hold a union (directly or nested) get `branch-<LABEL>`, the
  `mixed` value with every such union on that branch.
- `branch-default` (and `-low`): a union's default branch, under a discriminator value
  no label names; `no-branch`: such a value when the union has no default branch.

Same model, same values, on every run and machine: no `random`, no hash ordering.
"""
from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass
from decimal import Decimal

from rapidgen.model import ir
from rapidgen.cdr.typeinfo import CdrTypes, format_fixed, label_key, label_value

_F64 = {"max": [1.7976931348623157e308, 2.2250738585072014e-308, 0.1, 1.0 / 3.0],
        "low": [-1.7976931348623157e308, -0.0, 5e-324, -2.2250738585072014e-308]}
_F32 = {"max": [3.4028234663852886e38, 1.1754943508222875e-38, 0.10000000149011612, 0.3333333432674408],
        "low": [-3.4028234663852886e38, -0.0, 1.401298464324817e-45, -1.1754943508222875e-38]}
# Text to fill strings with: 1-, 2-, 3- and 4-byte UTF-8 characters.
_TEXT = "RAPID ünïcødé ✓ 火星探査 🚀 Ωμέγα "
_ASCII = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
_SMALL_BOUND = 16  # sequences bounded this tightly are filled to their bound (in `max`)
_OCTETS_MAX = 64
_MAX_CDEPTH = 4  # collections nested deeper than this are left empty


# Golden vectors are for reading and for cross-checking three languages: arrays beyond
# this many elements, and strings whose bound (times the array copies holding them) is
# beyond this many characters, are refused rather than sampled (they would take gigabytes:
# `max` fills strings to their bound).
MAX_ARRAY_ELEMENTS = 1 << 20
MAX_STRING_CHARS = 1 << 20


class SampleError(Exception):
    """A type that cannot be given a sample value; `loc` is the member or typedef naming it."""

    def __init__(self, message: str, loc=None) -> None:
        super().__init__(message)
        self.loc = loc


def _refuse_huge(model: ir.Model) -> None:
    """Every sample fills its arrays, and `max` its strings: refuse, before starting, any
    array or string too large to fill."""
    def check(t: ir.Type, where: ir.Declaration, loc, outer: int = 1) -> None:
        t = model.resolve_alias(t)
        if isinstance(t, ir.Array):
            total = outer
            for d in t.dims:
                total *= d
            if total > MAX_ARRAY_ELEMENTS:
                raise SampleError(f"'{where.scoped_name}' holds an array of {total} elements ({t}); "
                                  f"samples are made for arrays of at most {MAX_ARRAY_ELEMENTS}", loc)
            check(t.element, where, loc, total)  # arrays of (typedef'd) arrays multiply
        elif isinstance(t, ir.Sequence):
            check(t.element, where, loc)
        elif isinstance(t, ir.Map):
            check(t.key, where, loc)
            check(t.value, where, loc)
        elif isinstance(t, ir.String) and t.bound is not None and t.bound * outer > MAX_STRING_CHARS:
            copies = f" ({outer} of them in an array)" if outer > 1 else ""
            raise SampleError(f"'{where.scoped_name}' holds a string bounded to {t.bound} characters{copies}; "
                              f"samples fill strings to their bound, at most {MAX_STRING_CHARS} characters", loc)
    for d in model.declarations:
        if isinstance(d, ir.Struct):
            for m in d.members:
                check(m.type, d, m.loc)
        elif isinstance(d, ir.Union):
            for c in d.cases:
                check(c.member.type, d, c.member.loc)
        elif isinstance(d, ir.Typedef):
            check(d.type, d, d.loc)


@dataclass(frozen=True)
class Sample:
    type: str  # scoped name
    name: str  # variant
    value: object


class _Rng:
    """splitmix64: a fixed, version-independent pseudo-random sequence."""

    def __init__(self, seed: str) -> None:
        self.state = zlib.crc32(seed.encode("utf-8"))

    def next(self) -> int:
        self.state = (self.state + 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
        return z ^ (z >> 31)

    def below(self, n: int) -> int:
        return self.next() % n if n > 0 else 0

    def between(self, lo: int, hi: int) -> int:
        return lo + self.next() % (hi - lo + 1)


def text_of_bytes(size: int, ascii_only: bool = False, offset: int = 0) -> str:
    """A string of exactly `size` UTF-8 bytes, non-ASCII unless ascii_only."""
    source = _ASCII if ascii_only else _TEXT
    out: list[str] = []
    used = 0
    i = offset
    while used < size:
        ch = source[i % len(source)]
        n = len(ch.encode("utf-8"))
        if used + n > size:
            ch, n = _ASCII[i % len(_ASCII)], 1
        out.append(ch)
        used += n
        i += 1
    return "".join(out)


def _f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


class _Gen:
    def __init__(self, types: CdrTypes, mode: str, seed: str, branch: object = None) -> None:
        self.t = types
        self.mode = mode  # max | low | mixed
        self.rng = _Rng(seed)
        self.branch = branch  # a label key: unions take that branch where they have it
        self.counter = 0
        self.depth = 0
        self.turns: dict[str, int] = {}

    def tick(self) -> int:
        self.counter += 1
        return self.counter

    def value(self, t: ir.Type, cdepth: int = 0) -> object:
        r = self.t.resolve(t)
        self.depth += 1
        try:
            if self.depth > 40:
                return self.t.default_value(t)
            return self._value(r, cdepth)
        finally:
            self.depth -= 1

    def _value(self, r: ir.Type, cdepth: int) -> object:
        if isinstance(r, ir.Primitive):
            return self.primitive(r.name)
        if isinstance(r, ir.String):
            return self.string(r)
        if isinstance(r, ir.Sequence):
            n = self.length(r.bound, cdepth, octets=self.t.resolve(r.element) == ir.Primitive("octet"))
            return [self.value(r.element, cdepth + 1) for _ in range(n)]
        if isinstance(r, ir.Array):
            dims, elem = self.t.array_shape(r)
            return self.filled(dims, elem, cdepth)
        if isinstance(r, ir.Map):
            n = min(self.length(r.bound, cdepth), 3)
            pairs: list[list[object]] = []
            seen: set[object] = set()
            for _ in range(n):
                k = self.value(r.key, cdepth + 1)
                if isinstance(k, (str, int, float, bool)) and (type(k), k) in seen:
                    continue
                seen.add((type(k), k))
                pairs.append([k, self.value(r.value, cdepth + 1)])
            return pairs
        if isinstance(r, ir.Fixed):
            top = 10 ** r.digits - 1
            n = {"max": top, "low": -top}.get(self.mode, self.rng.between(-top, top))
            return format_fixed(n, 0) if r.scale == 0 else format_fixed(_scaled(n, r.scale), r.scale)
        if isinstance(r, ir.TypeRef):
            d = self.t.decl(r)
            if isinstance(d, ir.Struct):
                return {mi.member.name: self.member(mi.member, cdepth) for mi in self.t.members(d)}
            if isinstance(d, ir.Union):
                return self.union(d, cdepth)
            if isinstance(d, ir.Enum):
                names = [e.name for e in d.enumerators]
                if self.mode == "max":
                    return names[-1]
                if self.mode == "low":
                    return names[1 % len(names)]
                return names[self.rng.below(len(names))]
            if isinstance(d, ir.Bitmask):
                bits = [1 << v.position for v in d.values]
                if self.mode == "max":
                    return sum(bits)
                if self.mode == "low":
                    return bits[0] if bits else 0
                return sum(b for b in bits if self.rng.below(2))
            if isinstance(d, ir.Bitset):
                out: dict[str, object] = {}
                for f in self.t.bitset_fields(d):
                    if not f.name:
                        continue
                    if f.type.name == "boolean":
                        out[f.name] = self.mode != "low"
                    elif f.type.name.startswith("int"):
                        out[f.name] = (1 << (f.width - 1)) - 1 if self.mode == "max" else -(1 << (f.width - 1))
                    else:
                        out[f.name] = (1 << f.width) - 1 if self.mode == "max" else 0
                return out
        return self.t.default_value(r)

    def member(self, m: ir.Member, cdepth: int) -> object:
        if m.optional and self.mode == "low":
            return None
        if m.optional and self.mode == "mixed" and self.rng.below(2):
            return None
        return self.value(m.type, cdepth)

    def filled(self, dims: tuple[int, ...], elem: ir.Type, cdepth: int) -> list:
        if len(dims) == 1:
            return [self.value(elem, cdepth + 1) for _ in range(dims[0])]
        return [self.filled(dims[1:], elem, cdepth) for _ in range(dims[0])]

    def length(self, bound: int | None, cdepth: int, octets: bool = False) -> int:
        cap = bound if bound is not None else 1 << 30
        if cdepth >= _MAX_CDEPTH:  # deep inside collections (recursive types): stop
            return 0
        if self.mode == "low":
            return min(1, cap)
        if self.mode == "max":
            if octets:
                return min(cap, _OCTETS_MAX)
            if bound is not None and bound <= _SMALL_BOUND and cdepth == 0:
                return bound
            return min(cap, 3 if cdepth == 0 else 2)
        least = 1 if self.branch is not None else 0  # a branch variant must reach its unions
        return self.rng.between(min(least, cap), min(cap, 6 if octets else (4 if cdepth == 0 else 2)))

    def primitive(self, name: str) -> object:
        k = self.tick()
        if name == "boolean":
            return {"max": True, "low": False}.get(self.mode, bool(self.rng.below(2)))
        if name == "char8":
            return {"max": "~", "low": " "}.get(self.mode, _ASCII[self.rng.below(len(_ASCII))])
        if name == "char16":
            return {"max": "Ω", "low": "é"}.get(self.mode, "火星ΩAé"[self.rng.below(5)])
        if name in ("float32", "float64", "float128"):
            table = _F32 if name == "float32" else _F64
            if self.mode in table:
                return table[self.mode][k % 4]
            x = self.rng.between(-(1 << 20), 1 << 20) / 64.0  # exact in float32 too
            return _f32(x) if name == "float32" else x
        lo, hi = ir.INTEGER_RANGES[name]
        if self.mode == "max":
            return hi
        if self.mode == "low":
            return lo
        return self.rng.between(lo, hi)

    def string(self, r: ir.String) -> str:
        if r.wide:
            size = r.bound if r.bound is not None else 12
            if self.mode == "mixed":
                size = self.rng.between(0, min(size, 12))
            base = "Ωμέγα 火星 wide " if self.mode != "low" else _ASCII
            return "".join(base[i % len(base)] for i in range(size))
        if self.mode == "mixed":
            size = self.rng.between(0, min(r.bound or 40, 40))
            return text_of_bytes(size, offset=self.rng.below(len(_TEXT)))
        size = r.bound if r.bound is not None else 40
        return text_of_bytes(size, ascii_only=self.mode == "low", offset=self.tick() % 7)

    def union(self, d: ir.Union, cdepth: int) -> object:
        cases = [c for c in d.cases if c.labels]
        if not cases:
            return self.t.default_union(d)
        if self.branch is not None:
            for c in cases:
                for label in c.labels:
                    if label_key(label) == self.branch:
                        return {"discriminator": label_value(label), "value": self.value(c.member.type, cdepth)}
        if self.mode == "mixed":
            case = cases[self.rng.below(len(cases))]
        else:
            turn = self.turns.get(d.scoped_name, 0 if self.mode == "max" else len(cases) // 2)
            self.turns[d.scoped_name] = turn + 1
            case = cases[turn % len(cases)]  # consecutive unions walk through every branch
        return {"discriminator": label_value(case.labels[0]), "value": self.value(case.member.type, cdepth)}


def _scaled(n: int, scale: int) -> Decimal:
    return Decimal(n).scaleb(-scale)


def _unions_inside(types: CdrTypes, t: ir.Type, seen: set[str]) -> list[ir.Union]:
    """Unions reachable from a type (in first-reached order)."""
    r = types.resolve(t)
    if isinstance(r, (ir.Sequence,)):
        return _unions_inside(types, r.element, seen)
    if isinstance(r, ir.Array):
        return _unions_inside(types, r.element, seen)
    if isinstance(r, ir.Map):
        return _unions_inside(types, r.key, seen) + _unions_inside(types, r.value, seen)
    if not isinstance(r, ir.TypeRef) or r.name in seen:
        return []
    seen.add(r.name)
    d = types.decl(r)
    out: list[ir.Union] = []
    if isinstance(d, ir.Union):
        out.append(d)
        for c in d.cases:
            out += _unions_inside(types, c.member.type, seen)
    elif isinstance(d, ir.Struct):
        for mi in types.members(d):
            out += _unions_inside(types, mi.member.type, seen)
    return out


def _free_discriminator(types: CdrTypes, d: ir.Union) -> object | None:
    """A discriminator value no case label names (it selects the default branch, or no
    member), if the discriminator type has one."""
    used = {label_key(lab) for c in d.cases for lab in c.labels}
    r = types.resolve(d.discriminator)
    if isinstance(r, ir.TypeRef):
        e = types.decl(r)
        if isinstance(e, ir.Enum):
            for en in e.enumerators:
                if (False, en.value) not in used:
                    return en.name
        return None
    if isinstance(r, ir.Primitive):
        if r.name == "boolean":
            return next((b for b in (False, True) if (True, b) not in used), None)
        if r.name in ("char8", "char16"):
            return next((ch for ch in _ASCII if (False, ch) not in used), None)
        lo, hi = ir.INTEGER_RANGES.get(r.name, (0, 0))
        for x in range(max(lo, 0), min(hi, 1000) + 1):
            if (False, x) not in used:
                return x
    return None


def samples(model: ir.Model, types: CdrTypes | None = None) -> list[Sample]:
    t = types or CdrTypes(model)
    _refuse_huge(model)
    decls = sorted((d for d in model.declarations if isinstance(d, (ir.Struct, ir.Union))),
                   key=lambda d: d.scoped_name)
    out: list[Sample] = []
    for d in decls:
        ref = ir.TypeRef(d.scoped_name, d.kind)
        name = d.scoped_name
        out.append(Sample(name, "min", t.default_value(ref)))
        for mode in ("max", "low", "mixed"):
            out.append(Sample(name, mode, _Gen(t, mode, f"{name}/{mode}").value(ref)))
        if isinstance(d, ir.Union):
            for case in d.cases:
                for label in case.labels:
                    tag = str(label_value(label))
                    for mode, suffix in (("max", ""), ("low", "-low")):
                        g = _Gen(t, mode, f"{name}/{tag}{suffix}", branch=label_key(label))
                        out.append(Sample(name, f"branch-{tag}{suffix}", g.value(ref)))
            free = _free_discriminator(t, d)
            default = next((c for c in d.cases if c.is_default), None)
            if free is not None and default is not None:
                for mode, suffix in (("max", ""), ("low", "-low")):
                    g = _Gen(t, mode, f"{name}/default{suffix}")
                    out.append(Sample(name, f"branch-default{suffix}",
                                      {"discriminator": free, "value": g.value(default.member.type)}))
            elif free is not None:
                out.append(Sample(name, "no-branch", {"discriminator": free}))
        else:
            unions = _unions_inside(t, ref, set())
            labels: list[ir.Label] = []
            for u in unions:
                for case in u.cases:
                    for label in case.labels:
                        if label_key(label) not in [label_key(x) for x in labels]:
                            labels.append(label)
            for label in labels:
                tag = str(label_value(label))
                g = _Gen(t, "mixed", f"{name}/{tag}", branch=label_key(label))
                out.append(Sample(name, f"branch-{tag}", g.value(ref)))
    return out
