"""Hypothesis strategies for values of any Model type, in the codec's value form."""
from __future__ import annotations

from decimal import Decimal

from hypothesis import strategies as st

from rapidgen.model import ir
from rapidgen.cdr.typeinfo import CdrTypes, format_fixed, label_key, label_value

_TEXT = st.characters(blacklist_categories=("Cs",), blacklist_characters="\0")
_MAX_LEN = 4  # elements per generated collection (bounds permitting)
_MAX_DEPTH = 3  # collections nested deeper are empty (recursive types)
_ABSENT = object()  # a union discriminator that selects no member


def _cut_utf8(s: str, limit: int | None) -> str:
    if limit is None:
        return s
    while len(s.encode("utf-8")) > limit:
        s = s[:-1]
    return s


def _cut_utf16(s: str, limit: int | None) -> str:
    if limit is None:
        return s
    while len(s.encode("utf-16-le")) // 2 > limit:
        s = s[:-1]
    return s


def _hashable(k: object) -> object:
    return (type(k).__name__, k) if isinstance(k, (str, int, float, bool)) else repr(k)


class Strategies:
    def __init__(self, types: CdrTypes, nan: bool = False) -> None:
        self.t = types
        self.nan = nan

    def of(self, t: ir.Type | str, depth: int = 0) -> st.SearchStrategy:
        r = self.t.type_of(t) if isinstance(t, str) else self.t.resolve(t)
        if isinstance(r, ir.Primitive):
            return self.primitive(r.name)
        if isinstance(r, ir.String):
            if r.wide:
                return st.text(_TEXT, max_size=min(r.bound or 8, 8)).map(lambda s: _cut_utf16(s, r.bound))
            return st.text(_TEXT, max_size=min(r.bound or 12, 12)).map(lambda s: _cut_utf8(s, r.bound))
        if isinstance(r, ir.Sequence):
            cap = 0 if depth >= _MAX_DEPTH else min(r.bound if r.bound is not None else _MAX_LEN, _MAX_LEN)
            if cap == 0:
                return st.just([])
            if self.t.resolve(r.element) == ir.Primitive("octet"):
                return st.binary(max_size=cap * 4 if cap else 0).map(lambda b: list(b[:r.bound]))
            return st.lists(self.of(r.element, depth + 1), max_size=cap)
        if isinstance(r, ir.Array):
            dims, elem = self.t.array_shape(r)
            return self._array(dims, self.of(elem, depth + 1))
        if isinstance(r, ir.Map):
            cap = 0 if depth >= _MAX_DEPTH else min(r.bound if r.bound is not None else _MAX_LEN, _MAX_LEN)
            if cap == 0:
                return st.just([])
            pairs = st.lists(st.tuples(self.of(r.key, depth + 1), self.of(r.value, depth + 1)), max_size=cap,
                             unique_by=lambda p: _hashable(p[0]))
            return pairs.map(lambda ps: [list(p) for p in ps])
        if isinstance(r, ir.Fixed):
            top = 10 ** r.digits - 1
            return st.integers(-top, top).map(lambda n: format_fixed(Decimal(n).scaleb(-r.scale), r.scale))
        if isinstance(r, ir.TypeRef):
            d = self.t.decl(r)
            if isinstance(d, ir.Enum):
                return st.sampled_from([e.name for e in d.enumerators])
            if isinstance(d, ir.Bitmask):
                return st.sets(st.sampled_from([v.position for v in d.values])).map(lambda s: sum(1 << p for p in s))
            if isinstance(d, ir.Bitset):
                fields = {}
                for f in self.t.bitset_fields(d):
                    if not f.name:
                        continue
                    if f.type.name == "boolean":
                        fields[f.name] = st.booleans()
                    elif f.type.name.startswith("int"):
                        fields[f.name] = st.integers(-(1 << (f.width - 1)), (1 << (f.width - 1)) - 1)
                    else:
                        fields[f.name] = st.integers(0, (1 << f.width) - 1)
                return st.fixed_dictionaries(fields)
            if isinstance(d, ir.Struct):
                members = {}
                for mi in self.t.members(d):
                    s = self.of(mi.member.type, depth + 1)
                    members[mi.member.name] = st.one_of(st.none(), s) if mi.member.optional else s
                return st.fixed_dictionaries(members)
            if isinstance(d, ir.Union):
                return self.union(d, depth)
        raise AssertionError(f"no strategy for {t}")

    def _array(self, dims: tuple[int, ...], elem: st.SearchStrategy) -> st.SearchStrategy:
        if len(dims) == 1:
            return st.lists(elem, min_size=dims[0], max_size=dims[0])
        return st.lists(self._array(dims[1:], elem), min_size=dims[0], max_size=dims[0])

    def primitive(self, name: str) -> st.SearchStrategy:
        if name == "boolean":
            return st.booleans()
        if name == "char8":
            return st.characters(max_codepoint=0xFF)
        if name == "char16":
            return st.characters(max_codepoint=0xFFFF)
        if name == "float32":
            return st.floats(width=32, allow_nan=self.nan)
        if name in ("float64", "float128"):
            return st.floats(allow_nan=self.nan)
        lo, hi = ir.INTEGER_RANGES[name]
        return st.integers(lo, hi)

    def union(self, d: ir.Union, depth: int) -> st.SearchStrategy:
        options = []
        used = {label_key(lab) for c in d.cases for lab in c.labels}
        for case in d.cases:
            value = self.of(case.member.type, depth + 1)
            if case.labels:
                options.append(st.tuples(st.sampled_from([label_value(x) for x in case.labels]), value))
        free = self.free_discriminators(d, used)
        default = next((c for c in d.cases if c.is_default), None)
        if free is not None:
            value = self.of(default.member.type, depth + 1) if default is not None else st.just(_ABSENT)
            options.append(st.tuples(free, value))
        if not options:
            return st.nothing()
        return st.one_of(options).map(
            lambda p: {"discriminator": p[0]} if p[1] is _ABSENT else {"discriminator": p[0], "value": p[1]})

    def free_discriminators(self, d: ir.Union, used: set) -> st.SearchStrategy | None:
        r = self.t.resolve(d.discriminator)
        if isinstance(r, ir.TypeRef):
            e = self.t.decl(r)
            names = [x.name for x in e.enumerators if (False, x.value) not in used]  # type: ignore[union-attr]
            return st.sampled_from(names) if names else None
        if r.name == "boolean":  # type: ignore[union-attr]
            free = [b for b in (False, True) if (True, b) not in used]
            return st.sampled_from(free) if free else None
        if r.name in ("char8", "char16"):  # type: ignore[union-attr]
            return st.characters(max_codepoint=0xFF if r.name == "char8" else 0xFFFF).filter(  # type: ignore[union-attr]
                lambda c: (False, c) not in used)
        lo, hi = ir.INTEGER_RANGES[r.name]  # type: ignore[union-attr]
        return st.integers(lo, hi).filter(lambda x: (False, x) not in used)
