"""How one type expression changed between OLD and NEW, and structural fingerprints.

A verdict is the worst of: "changed" (not assignable), "shrunk" (a bound got smaller),
"alias" (spelt differently, same wire form), "grown" (a bound got larger: allowed).
Named types (struct, union, enum, bitmask) with the same name on both sides are judged at
their own declaration, once; with different names they are compared by fingerprint.
"""
from __future__ import annotations

from rapidgen.model import ir

MAX_DEPTH = 100  # nested named types followed when fingerprinting
ORDER = ("same", "grown", "alias", "shrunk", "changed")


def worst(*verdicts: str) -> str:
    return max(verdicts, key=ORDER.index, default="same")


def _bound(old: int | None, new: int | None) -> str:
    """None is unbounded."""
    if old == new:
        return "same"
    if new is None or (old is not None and new > old):
        return "grown"
    return "shrunk"


class Fingerprints:
    """A hashable canonical form of a type: equal fingerprints, same wire form and names.

    A named type's fingerprint is interned as a number in a table both sides share, so
    fingerprints stay flat (a chain of 10,000 structs is not a 10,000-deep tuple), and the
    memo is filled in dependency order, so resolving one type recurses one level."""

    def __init__(self, model: ir.Model, interned: dict[object, int]) -> None:
        self.model = model
        self.memo: dict[str, object] = {}
        self.busy: set[str] = set()
        self.interned = interned
        self.warm = False

    def member_id(self, m: ir.Member, index: int) -> int:
        # Member.member_id is resolved in the IR (XTypes 7.3.1.2.1.1); index: a fallback
        return getattr(m, "member_id", index)

    def of(self, t: ir.Type) -> object:
        t = self.model.resolve_alias(t)
        if isinstance(t, ir.Primitive):
            return ("p", t.name)
        if isinstance(t, ir.String):
            return ("s", t.bound, t.wide)
        if isinstance(t, ir.Sequence):
            return ("q", self.of(t.element), t.bound)
        if isinstance(t, ir.Array):
            return ("a", t.dims, self.of(t.element))
        if isinstance(t, ir.Map):
            return ("m", self.of(t.key), self.of(t.value), t.bound)
        if isinstance(t, ir.Fixed):
            return ("f", t.digits, t.scale)
        return self.decl(t.name)

    def decl(self, name: str) -> object:
        if not self.warm:
            self.warm = True
            for d in self.model.declarations:  # dependency order
                if not isinstance(d, ir.Const):
                    self.decl(d.scoped_name)
        if name in self.memo:
            return self.memo[name]
        if name in self.busy:  # recursive types: the name stands for the rest
            return ("rec", name)
        if len(self.busy) > MAX_DEPTH:  # bounded on hostile chains: deeper types compare by name
            return ("deep", name)
        self.busy.add(name)
        try:
            fp = self.interned.setdefault(self._decl(self.model.get(name), name), len(self.interned))
        finally:
            self.busy.discard(name)
        self.memo[name] = fp
        return fp

    def _decl(self, d: ir.Declaration | None, name: str) -> object:
        if isinstance(d, ir.Struct):
            members = self.model.all_members(d)
            return ("struct", d.extensibility, d.keys, tuple(
                (m.name, self.of(m.type), m.optional, self.member_id(m, i)) for i, m in enumerate(members)))
        if isinstance(d, ir.Union):
            return ("union", d.extensibility, self.of(d.discriminator), tuple(
                (labels(c), c.is_default, c.member.name, self.of(c.member.type)) for c in d.cases))
        if isinstance(d, ir.Enum):
            return ("enum", d.extensibility, d.bit_bound, tuple((e.name, e.value) for e in d.enumerators))
        if isinstance(d, ir.Bitmask):
            return ("bitmask", d.bit_bound, tuple((v.name, v.position) for v in d.values))
        if isinstance(d, ir.Bitset):
            return ("bitset", tuple((f.name, f.width, f.type.name) for f in self.model.all_fields(d)))
        if isinstance(d, ir.Typedef):
            return self.of(d.type)
        return ("named", name)


def labels(case: ir.UnionCase) -> frozenset:
    return frozenset(ir.label_key(x) for x in case.labels)


class TypeCompare:
    def __init__(self, old: ir.Model, new: ir.Model) -> None:
        self.old, self.new = old, new
        interned: dict[object, int] = {}
        self.ofp, self.nfp = Fingerprints(old, interned), Fingerprints(new, interned)

    def verdict(self, o: ir.Type, n: ir.Type) -> str:
        if isinstance(o, ir.TypeRef) and isinstance(n, ir.TypeRef) and o.name == n.name and o.kind == n.kind:
            return "same"  # judged at the declaration itself
        ro, rn = self.old.resolve_alias(o), self.new.resolve_alias(n)
        spelt = "alias" if (o != n and (o != ro or n != rn)) else "same"
        return worst(spelt, self._resolved(ro, rn))

    def _resolved(self, o: ir.Type, n: ir.Type) -> str:
        if type(o) is not type(n):
            return "changed"
        # (same class from here: each test names it on both sides for the checker)
        if isinstance(o, ir.Primitive) and isinstance(n, ir.Primitive):
            return "same" if o.name == n.name else "changed"
        if isinstance(o, ir.String) and isinstance(n, ir.String):
            return "changed" if o.wide != n.wide else _bound(o.bound, n.bound)
        if isinstance(o, ir.Sequence) and isinstance(n, ir.Sequence):
            return worst(self.verdict(o.element, n.element), _bound(o.bound, n.bound))
        if isinstance(o, ir.Array) and isinstance(n, ir.Array):
            if o.dims != n.dims:
                return "changed"
            return self.verdict(o.element, n.element)
        if isinstance(o, ir.Map) and isinstance(n, ir.Map):
            return worst(self.verdict(o.key, n.key), self.verdict(o.value, n.value),
                         _bound(o.bound, n.bound))
        if isinstance(o, ir.Fixed):
            return "same" if o == n else "changed"
        assert isinstance(o, ir.TypeRef) and isinstance(n, ir.TypeRef)
        if o.name == n.name:
            return "same"
        return "alias" if self.ofp.decl(o.name) == self.nfp.decl(n.name) else "changed"
