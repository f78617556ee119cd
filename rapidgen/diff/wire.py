"""Wire rules: two resolved models compared declaration by declaration (XTypes 1.3 7.2.4).

Members of structs are compared flattened (base members first, as on the wire): for
@final and @appendable by name and position, for @mutable by member id.
"""
from __future__ import annotations

from rapidgen.diagnostics import SourceLoc
from rapidgen.diff.rules import Finding, rule
from rapidgen.diff.types import TypeCompare, labels
from rapidgen.model import ir

TYPE_KINDS = (ir.Struct, ir.Union, ir.Enum, ir.Bitmask, ir.Bitset)


class WireDiff:
    def __init__(self, old: ir.Model, new: ir.Model) -> None:
        self.old, self.new = old, new
        self.types = TypeCompare(old, new)
        self.out: list[Finding] = []

    def add(self, rule_id: str, subject: str, message: str, old: object, new: object) -> None:
        self.out.append(Finding(rule(rule_id), subject, message, _loc(old), _loc(new)))

    # -- declarations -------------------------------------------------------------------
    def run(self) -> list[Finding]:
        new_names = self.new.by_name
        gone = [d for d in self.old.declarations if d.scoped_name not in new_names]
        added = [d for d in self.new.declarations if d.scoped_name not in self.old.by_name]
        for d in self.old.declarations:
            n = new_names.get(d.scoped_name)
            if n is not None:
                self.declaration(d, n)
        self.removed(gone, added)
        return self.out

    def removed(self, gone: list, added: list) -> None:
        twins: dict[object, ir.Declaration] = {}
        for d in added:
            if isinstance(d, TYPE_KINDS):
                twins.setdefault(self.types.nfp.decl(d.scoped_name), d)
        for d in gone:
            name = d.scoped_name
            if isinstance(d, ir.Typedef):
                self.add("SRC-TYPEDEF-01", name, f"typedef '{name}' removed", d, None)
            elif isinstance(d, ir.Const):
                self.add("SRC-CONST-02", name, f"constant '{name}' removed", d, None)
            elif isinstance(d, TYPE_KINDS):
                twin = twins.get(self.types.ofp.decl(name))
                if twin is not None:
                    self.add("WIRE-TYPE-02", name, f"type '{name}' renamed to '{twin.scoped_name}'", d, twin)
                else:
                    self.add("WIRE-TYPE-01", name, f"{d.kind} '{name}' removed", d, None)

    def declaration(self, o: ir.Declaration, n: ir.Declaration) -> None:
        name = o.scoped_name
        if o.kind != n.kind:
            self.add("WIRE-TYPE-03", name, f"'{name}' was a {o.kind}, is now a {n.kind}", o, n)
            return
        ext_o, ext_n = getattr(o, "extensibility", None), getattr(n, "extensibility", None)
        if ext_o != ext_n:
            self.add("WIRE-TYPE-04", name, f"'{name}' was @{ext_o}, is now @{ext_n}", o, n)
            return
        # (same kind from here: each test names the class on both sides for the checker)
        if isinstance(o, ir.Struct) and isinstance(n, ir.Struct):
            self.struct(o, n)
        elif isinstance(o, ir.Union) and isinstance(n, ir.Union):
            self.union(o, n)
        elif isinstance(o, ir.Enum) and isinstance(n, ir.Enum):
            self.enum(o, n)
        elif isinstance(o, (ir.Bitmask, ir.Bitset)):
            if self.types.ofp.decl(name) != self.types.nfp.decl(name) and not self._bits_grown(o, n):
                self.add("WIRE-BITMASK-01", name, f"{o.kind} '{name}' changed its bits", o, n)
        elif isinstance(o, ir.Typedef) and isinstance(n, ir.Typedef):
            self.typedef(o, n)
        elif isinstance(o, ir.Const) and isinstance(n, ir.Const):
            self.const(o, n)

    def _bits_grown(self, o, n) -> bool:
        """A bitmask that only gained flags (same bit bound) keeps every old value's meaning."""
        if not isinstance(o, ir.Bitmask):
            return False
        old = {(v.name, v.position) for v in o.values}
        return o.bit_bound == n.bit_bound and old <= {(v.name, v.position) for v in n.values}

    def typedef(self, o: ir.Typedef, n: ir.Typedef) -> None:
        v = self.types.verdict(o.type, n.type)
        what = f"typedef '{o.scoped_name}' was {o.type}, is now {n.type}"
        self._type_verdict(v, "WIRE-TYPEDEF-01", o.scoped_name, what, o, n)

    def const(self, o: ir.Const, n: ir.Const) -> None:
        if o.value == n.value and str(o.type) == str(n.type):
            return
        topic = o.name.endswith("_TOPIC") and isinstance(o.value, str)
        self.add("WIRE-TOPIC-01" if topic else "SRC-CONST-01", o.scoped_name,
                 f"'{o.scoped_name}' was {o.value!r}, is now {n.value!r}", o, n)

    def _type_verdict(self, v: str, changed_rule: str, subject: str, what: str, o, n) -> None:
        if v == "changed":
            self.add(changed_rule, subject, what, o, n)
        elif v == "shrunk":
            self.add("WIRE-BOUND-01", subject, what, o, n)
        elif v == "alias":
            self.add("SRC-TYPE-01", subject, what, o, n)

    def member_type(self, subject: str, o: ir.Member, n: ir.Member) -> None:
        what = f"'{subject}' was {o.type}, is now {n.type}"
        self._type_verdict(self.types.verdict(o.type, n.type), "WIRE-MEMBER-06", subject, what, o, n)
        if o.optional != n.optional:
            now = "optional" if n.optional else "mandatory"
            self.add("WIRE-MEMBER-07", subject, f"'{subject}' is now {now}", o, n)

    # -- structs ------------------------------------------------------------------------
    def struct(self, o: ir.Struct, n: ir.Struct) -> None:
        om, nm = self.old.all_members(o), self.new.all_members(n)
        if o.extensibility == "mutable":
            self.mutable(o, n, om, nm)
        else:
            self.ordered(o, n, om, nm)
        if o.keys != n.keys:
            self.add("WIRE-KEY-01", o.scoped_name, f"key of '{o.scoped_name}' was ({', '.join(o.keys)}), "
                     f"is now ({', '.join(n.keys)})", o, n)

    def ordered(self, o: ir.Struct, n: ir.Struct, om: tuple, nm: tuple) -> None:
        s = o.scoped_name
        onames, nnames = [m.name for m in om], [m.name for m in nm]
        removed = [i for i, m in enumerate(om) if m.name not in nnames]
        added = [j for j, m in enumerate(nm) if m.name not in onames]
        # A member at the same position with the same type and another name: renamed.
        renamed = {i: i for i in removed if i in added
                   and self.types.verdict(om[i].type, nm[i].type) in ("same", "grown")}
        for i in renamed:
            self.add("WIRE-MEMBER-05", f"{s}.{om[i].name}", f"'{s}.{om[i].name}' renamed to '{nm[i].name}'",
                     om[i], nm[i])
        removed = [i for i in removed if i not in renamed]
        added = [j for j in added if j not in renamed]
        kept_o = [i for i in range(len(om)) if i not in removed]  # still there (or renamed)
        kept_n = [j for j in range(len(nm)) if j not in added]
        last_o = kept_o[-1] if kept_o else -1
        last_n = kept_n[-1] if kept_n else -1
        for i in removed:
            trailing = o.extensibility == "appendable" and i > last_o and not added
            rid = "SRC-MEMBER-01" if trailing else "WIRE-MEMBER-01"
            self.add(rid, f"{s}.{om[i].name}", f"member '{s}.{om[i].name}' removed", om[i], n)
        for j in added:
            if o.extensibility == "final":
                self.add("WIRE-MEMBER-02", f"{s}.{nm[j].name}", f"member '{s}.{nm[j].name}' added to @final "
                         f"'{s}'", o, nm[j])
            elif j < last_n or removed:
                self.add("WIRE-MEMBER-03", f"{s}.{nm[j].name}", f"member '{s}.{nm[j].name}' inserted before "
                         f"'{nm[last_n].name}'" if j < last_n else f"member '{s}.{nm[j].name}' added where "
                         "members were removed", o, nm[j])
        # Order of the members on both sides (renamed ones under their new name).
        old_order = [nm[renamed[i]].name if i in renamed else om[i].name for i in kept_o]
        new_order = [nm[j].name for j in kept_n]
        if old_order != new_order:
            first = next(k for k in range(len(new_order)) if old_order[k] != new_order[k])
            moved = new_order[first]
            self.add("WIRE-MEMBER-04", s, f"members of '{s}' reordered: '{moved}' was at position "
                     f"{old_order.index(moved) + 1}, is at {first + 1}", om[onames.index(moved)] if moved in onames
                     else o, nm[nnames.index(moved)])
        by_new = {m.name: m for m in nm}
        for i in kept_o:
            m = om[i]
            other = nm[renamed[i]] if i in renamed else by_new[m.name]
            self.member_type(f"{s}.{other.name}", m, other)

    def mutable(self, o: ir.Struct, n: ir.Struct, om: tuple, nm: tuple) -> None:
        s = o.scoped_name
        ids = self.types.ofp.member_id, self.types.nfp.member_id
        new_ids = {ids[1](m, i): m for i, m in enumerate(nm)}
        new_names = {m.name: (ids[1](m, i), m) for i, m in enumerate(nm)}
        for i, m in enumerate(om):
            mid = ids[0](m, i)
            sub = f"{s}.{m.name}"
            same_id = new_ids.get(mid)
            if same_id is not None and same_id.name != m.name:
                self.add("WIRE-MEMBER-08", sub, f"member id {mid} of '{s}' was '{m.name}', is now "
                         f"'{same_id.name}'", m, same_id)
                continue
            if same_id is not None:
                self.member_type(sub, m, same_id)
                continue
            if m.name in new_names:
                nid, nmem = new_names[m.name]
                self.add("WIRE-MEMBER-09", sub, f"member id of '{sub}' was {mid}, is now {nid}", m, nmem)
                self.member_type(sub, m, nmem)
            elif not m.key:  # a removed key member is WIRE-KEY-01
                self.add("SRC-MEMBER-02", sub, f"member '{sub}' removed from @mutable '{s}'", m, n)

    # -- unions -------------------------------------------------------------------------
    def union(self, o: ir.Union, n: ir.Union) -> None:
        s = o.scoped_name
        v = self.types.verdict(o.discriminator, n.discriminator)
        what = f"discriminator of '{s}' was {o.discriminator}, is now {n.discriminator}"
        self._type_verdict("changed" if v == "shrunk" else v, "WIRE-UNION-01", s, what, o, n)
        ocases = {c.member.name: c for c in o.cases}
        ncases = {c.member.name: c for c in n.cases}
        gone = [c for c in o.cases if c.member.name not in ncases]
        new = [c for c in n.cases if c.member.name not in ocases]
        for c in list(gone):  # same labels, another name: renamed
            twin = next((x for x in new if labels(x) == labels(c) and x.is_default == c.is_default), None)
            if twin is not None:
                gone.remove(c)
                new.remove(twin)
                self.add("WIRE-MEMBER-05", f"{s}.{c.member.name}", f"case '{s}.{c.member.name}' renamed to "
                         f"'{twin.member.name}'", c.member, twin.member)
                self.member_type(f"{s}.{twin.member.name}", c.member, twin.member)
        for c in gone:
            self.add("WIRE-UNION-03", f"{s}.{c.member.name}", f"case '{s}.{c.member.name}' removed", c.member, n)
        for c in new:
            if o.extensibility == "final":
                self.add("WIRE-UNION-04", f"{s}.{c.member.name}", f"case '{s}.{c.member.name}' added to @final "
                         f"'{s}'", o, c.member)
        for name, c in ocases.items():
            nc = ncases.get(name)
            if nc is None:
                continue
            sub = f"{s}.{name}"
            if labels(c) != labels(nc):
                was = ", ".join(str(x) for x in c.labels) or "none"
                now = ", ".join(str(x) for x in nc.labels) or "none"
                self.add("WIRE-UNION-02", sub, f"labels of case '{sub}' were {was}, are now {now}", c.member, nc.member)
            if c.is_default != nc.is_default:
                self.add("WIRE-UNION-05", sub, f"case '{sub}' {'is now' if nc.is_default else 'is no longer'} "
                         "the default case", c.member, nc.member)
            self.member_type(sub, c.member, nc.member)

    # -- enums --------------------------------------------------------------------------
    def enum(self, o: ir.Enum, n: ir.Enum) -> None:
        s = o.scoped_name
        if o.bit_bound != n.bit_bound:
            self.add("WIRE-ENUM-05", s, f"@bit_bound of '{s}' was {o.bit_bound}, is now {n.bit_bound}", o, n)
        new_by_name = {e.name: e for e in n.enumerators}
        old_names = {e.name for e in o.enumerators}
        added = [e for e in n.enumerators if e.name not in old_names]
        for e in o.enumerators:
            ne = new_by_name.get(e.name)
            if ne is not None:
                if ne.value != e.value:
                    self.add("WIRE-ENUM-01", f"{s}::{e.name}", f"'{s}::{e.name}' was {e.value}, is now {ne.value}",
                             e, ne)
                continue
            twin = next((x for x in added if x.value == e.value), None)
            if twin is not None:
                added.remove(twin)
                self.add("WIRE-ENUM-04", f"{s}::{e.name}", f"'{s}::{e.name}' renamed to '{twin.name}'", e, twin)
            else:
                self.add("WIRE-ENUM-02", f"{s}::{e.name}", f"enumerator '{s}::{e.name}' removed", e, n)
        if o.extensibility == "final":
            for e in added:
                self.add("WIRE-ENUM-03", f"{s}::{e.name}", f"enumerator '{s}::{e.name}' added to @final '{s}'", o, e)


def wire_diff(old: ir.Model, new: ir.Model) -> list[Finding]:
    return WireDiff(old, new).run()


def _loc(x: object) -> SourceLoc | None:
    """Where a declaration, member or enumerator is (x itself when it is a location)."""
    loc = getattr(x, "loc", x)
    return loc if isinstance(loc, SourceLoc) else None
