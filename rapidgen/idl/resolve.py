"""Resolution: syntax tree -> Model.

Builds the symbol table (re-opened modules merge, forward declarations meet their
definitions), resolves scoped names relative to the enclosing scopes or from the root,
evaluates constants, bounds and union labels, checks inheritance, members and
annotations, then hands the declarations to keys.py (key paths) and order.py
(recursion check and dependency order). Every problem is a diagnostic; resolution goes
on past errors so one run reports as many as it can.
"""
from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal
from typing import Callable, TypeVar, cast

from rapidgen.diagnostics import DiagnosticSink, SourceLoc, did_you_mean
from rapidgen.idl import ast
from rapidgen.model import ir
from rapidgen.idl.annotations import AnnotationChecker, Checked
from rapidgen.idl.consts import ConstEvaluator, Target, Typed, target_for_primitive
from rapidgen.idl.facts import MemberIds, discriminator_default, enum_default, union_default
from rapidgen.idl.keys import apply_keylists, compute_keys
from rapidgen.model.order import check_recursion, dependency_order

_TYPE_KINDS = frozenset({"struct", "union", "enum", "bitmask", "bitset", "typedef", "native", "forward"})
_MAX_TYPE_NESTING = 100
_MAX_SCOPE_DEPTH = 100  # modules (and valuetypes) nested in one another
_MAX_NAME_HINTS = 100  # unknown names that get a did-you-mean hint (each costs a scan of all names)
_DISCRIMINATOR_PRIMITIVES = frozenset({"int8", "uint8", "int16", "uint16", "int32", "uint32", "int64",
                                       "uint64", "char8", "char16", "boolean", "octet"})


@dataclass
class _Sym:
    kind: str  # module | struct | union | enum | bitmask | bitset | typedef | const | native | enumerator | forward
    scoped: str
    decl: object  # the syntax node, of the class its kind names (see _decl)
    scope: tuple[str, ...]  # the scope the declaration's own names are resolved in
    loc: SourceLoc
    forward_kind: str = ""  # for kind == "forward": struct | union | valuetype
    extra: ast.Declarator | tuple[str, int] | None = None  # typedef: the Declarator; enumerator: (enum scoped name, index)


_D = TypeVar("_D")


def _decl(sym: _Sym, node: type[_D]) -> _D:
    """sym's syntax node, which its kind says is a `node` (a wrong one is a resolver bug)."""
    assert isinstance(sym.decl, node), (sym.kind, type(sym.decl))
    return sym.decl


def _join(parts: tuple[str, ...]) -> str:
    return "::".join(parts)


class Resolver:
    def __init__(self, sink: DiagnosticSink) -> None:
        self.sink = sink
        self.syms: dict[str, _Sym] = {}
        self.modules: dict[str, ir.Module] = {}
        self.pragmas: list[tuple[ast.KeylistPragma, tuple[str, ...]]] = []
        self.done: dict[str, ir.Declaration | None] = {}
        self.busy: dict[str, None] = {}  # being resolved, in order (an ordered set)
        self.too_deep = False  # a "nested too deeply" error was reported (once is enough)
        self._lookups: dict[tuple, _Sym | None] = {}
        self._by_enum: dict[str, dict[str, ir.Enumerator]] = {}  # enum -> its enumerators by name
        self._pools: dict[frozenset[str], list[str]] = {}  # declaration names of some kinds, for hints
        self._hints_left = _MAX_NAME_HINTS
        self.evaluator = ConstEvaluator(sink)
        self.annotations = AnnotationChecker(sink, self.evaluator)

    # == symbol table =====================================================================
    def _add(self, sym: _Sym) -> None:
        prev = self.syms.get(sym.scoped)
        if prev is None:
            self.syms[sym.scoped] = sym
            return
        if prev.kind == "module" and sym.kind == "module":
            return
        if sym.kind == "forward" and (prev.kind == "forward" or _matches_forward(prev, sym.forward_kind)):
            return
        if prev.kind == "forward" and _matches_forward(sym, prev.forward_kind):
            self.syms[sym.scoped] = sym
            return
        self.sink.error("RG0204", f"'{sym.scoped}' is already defined", sym.loc,
                        f"previous definition at {prev.loc}")

    def _collect(self, defs: tuple[ast.Definition, ...], scope: tuple[str, ...]) -> None:
        for d in defs:
            if isinstance(d, (ast.ModuleDecl, ast.StructDecl)) and len(scope) >= _MAX_SCOPE_DEPTH:
                # Name lookups walk every enclosing scope: thousands of levels make them quadratic.
                if not self.too_deep:
                    self.sink.error("RG0201", f"'{d.name}' is nested more than {_MAX_SCOPE_DEPTH} scopes deep",
                                    d.loc, "flatten the modules")
                self.too_deep = True
                continue
            if isinstance(d, ast.ModuleDecl):
                path = scope + (d.name,)
                self._add(_Sym("module", _join(path), d, path, d.loc))
                if _join(path) not in self.modules and self.syms[_join(path)].kind == "module":
                    self.modules[_join(path)] = ir.Module(d.name, _join(path), d.loc)
                self._collect(d.definitions, path)
            elif isinstance(d, ast.StructDecl):
                path = scope + (d.name,)
                self._add(_Sym("struct", _join(path), d, path, d.loc))
                self._collect(d.exports, path)
            elif isinstance(d, ast.ForwardDecl):
                self._add(_Sym("forward", _join(scope + (d.name,)), d, scope, d.loc, d.kind))
            elif isinstance(d, ast.UnionDecl):
                self._add(_Sym("union", _join(scope + (d.name,)), d, scope + (d.name,), d.loc))
            elif isinstance(d, ast.EnumDecl):
                self._add(_Sym("enum", _join(scope + (d.name,)), d, scope, d.loc))
                seen: set[str] = set()
                for i, e in enumerate(d.enumerators):
                    enum_name = _join(scope + (d.name,))
                    if e.name in seen:
                        continue  # reported once, as a duplicate enumerator, by _resolve_enum
                    seen.add(e.name)
                    # IDL puts enumerators in the enclosing scope; E::X is accepted too.
                    self._add(_Sym("enumerator", _join(scope + (e.name,)), e, scope, e.loc, extra=(enum_name, i)))
                    self.syms.setdefault(_join(scope + (d.name, e.name)),
                                         _Sym("enumerator", _join(scope + (d.name, e.name)), e, scope, e.loc,
                                              extra=(enum_name, i)))
            elif isinstance(d, ast.BitmaskDecl):
                self._add(_Sym("bitmask", _join(scope + (d.name,)), d, scope, d.loc))
            elif isinstance(d, ast.BitsetDecl):
                self._add(_Sym("bitset", _join(scope + (d.name,)), d, scope, d.loc))
            elif isinstance(d, ast.TypedefDecl):
                for decl in d.declarators:
                    self._add(_Sym("typedef", _join(scope + (decl.name,)), d, scope, decl.loc, extra=decl))
            elif isinstance(d, ast.ConstDecl):
                self._add(_Sym("const", _join(scope + (d.name,)), d, scope, d.loc))
            elif isinstance(d, ast.NativeDecl):
                self._add(_Sym("native", _join(scope + (d.name,)), d, scope, d.loc))
            elif isinstance(d, ast.KeylistPragma):
                self.pragmas.append((d, scope))
            elif isinstance(d, ast.AnnotationDecl):
                self.annotations.declared.add(d.name)

    # == lookup ===========================================================================
    def lookup(self, name: ast.ScopedName, scope: tuple[str, ...]) -> _Sym | None:
        """The symbol a name means in scope: from the root when absolute, else searched outward."""
        memo_key = (name.parts, name.absolute, scope)
        if memo_key in self._lookups:  # the symbol table is complete before any lookup
            return self._lookups[memo_key]
        found = None
        if name.absolute:
            found = self.syms.get(_join(name.parts))
        else:
            for i in range(len(scope), -1, -1):
                found = self.syms.get(_join(scope[:i] + name.parts))
                if found is not None:
                    break
        self._lookups[memo_key] = found
        return found

    def _unknown(self, name: ast.ScopedName, scope: tuple[str, ...], what: str, kinds: frozenset[str]) -> None:
        hint = None
        # A hint compares the name with every declaration: past the first few unknown names
        # (a file of thousands of misspellings), that would make the run quadratic.
        if self._hints_left > 0:
            self._hints_left -= 1
            pool = self._pools.get(kinds)
            if pool is None:
                pool = self._pools[kinds] = [s.scoped.rsplit("::", 1)[-1] for s in self.syms.values()
                                             if s.kind in kinds]
            hint = did_you_mean(name.parts[-1], pool)
        self.sink.error("RG0203", f"unknown {what} '{name}'", name.loc, hint)

    # == constants ========================================================================
    def _name_value(self, scope: tuple[str, ...]):
        def lookup(name: ast.ScopedName) -> Typed | None:
            sym = self.lookup(name, scope)
            if sym is None:
                self._unknown(name, scope, "constant", frozenset({"const", "enumerator"}))
                return None
            if sym.kind == "enumerator":
                assert isinstance(sym.extra, tuple)
                enum = self.declaration(self.syms[sym.extra[0]])
                if not isinstance(enum, ir.Enum):
                    return None
                # By name: enumerators with errors are left out of the IR, so indexes shift.
                e = self._enumerators(enum).get(_decl(sym, ast.EnumeratorDecl).name)
                if e is None:  # this enumerator's own error is already reported
                    return None
                return Typed("enum", ir.EnumValue(enum.scoped_name, e.name, e.value))
            if sym.kind != "const":
                self.sink.error("RG0405", f"'{name}' is a {sym.kind}, not a constant", name.loc)
                return None
            const = self.declaration(sym)
            if not isinstance(const, ir.Const):
                return None
            return Typed(_category(self._target(const.type)), const.value)
        return lookup

    def _enumerators(self, enum: ir.Enum) -> dict[str, ir.Enumerator]:
        """An enum's enumerators by name, built once (a scan per use was quadratic)."""
        index = self._by_enum.get(enum.scoped_name)
        if index is None:
            index = self._by_enum[enum.scoped_name] = {e.name: e for e in enum.enumerators}
        return index

    def _target(self, t: ir.Type) -> Target:
        """What a constant of IR type t must hold."""
        t = self._alias(t)
        if isinstance(t, ir.Primitive):
            return target_for_primitive(t.name) if t.name != "octet" else Target("int", "octet")
        if isinstance(t, ir.String):
            return Target("string", "", t.bound, t.wide)
        if isinstance(t, ir.Fixed):
            return Target("fixed", "fixed")
        if isinstance(t, ir.TypeRef) and t.kind == "enum":
            return Target("enum", t.name)
        return Target("any")

    def _positive(self, expr: ast.Expr, scope: tuple[str, ...], what: str) -> int | None:
        value = self.evaluator.evaluate(expr, Target("int", "int64"), self._name_value(scope))
        if value is None:
            return None
        assert isinstance(value, int)  # the int64 target converts or fails
        if value <= 0:
            self.sink.error("RG0404", f"{what} must be positive, not {value}", expr.loc)
            return None
        if value > 2**32 - 1:
            self.sink.error("RG0402", f"{what} {value} does not fit in 32 bits", expr.loc)
            return None
        return value

    # == types ============================================================================
    def _alias(self, t: ir.Type) -> ir.Type:
        return ir.unalias(t, self._get)

    def _get(self, scoped: str) -> ir.Declaration | None:
        """The declaration of a scoped name, resolved on demand."""
        sym = self.syms.get(scoped)
        return self.declaration(sym) if sym is not None else None

    def type_of(self, spec: ast.TypeSpec, scope: tuple[str, ...], depth: int = 0) -> ir.Type | None:
        if depth > _MAX_TYPE_NESTING:  # sequence<sequence<...>>: later stages recurse on types
            self.sink.error("RG0201", f"type nested more than {_MAX_TYPE_NESTING} levels deep", spec.loc)
            return None
        if isinstance(spec, ast.BaseType):
            return ir.Primitive(spec.name)
        if isinstance(spec, ast.NamedType):
            sym = self.lookup(spec.name, scope)
            if sym is None:
                self._unknown(spec.name, scope, "type", _TYPE_KINDS)
                return None
            if sym.kind not in _TYPE_KINDS:
                self.sink.error("RG0206", f"'{spec.name}' is a {sym.kind}, not a type", spec.loc)
                return None
            if sym.kind == "forward":
                self.sink.error("RG0309", f"'{sym.scoped}' is declared but never defined", spec.loc,
                                f"define it after its forward declaration at {sym.loc}")
                return None
            return ir.TypeRef(sym.scoped, cast(ir.TypeKind, sym.kind))  # a type kind, checked above
        if isinstance(spec, ast.SequenceType):
            elem = self.type_of(spec.element, scope, depth + 1)
            bound = self._positive(spec.bound, scope, "sequence bound") if spec.bound is not None else None
            if elem is None or (spec.bound is not None and bound is None):
                return None
            return ir.Sequence(elem, bound)
        if isinstance(spec, ast.StringType):
            bound = self._positive(spec.bound, scope, "string bound") if spec.bound is not None else None
            if spec.bound is not None and bound is None:
                return None
            return ir.String(bound, spec.wide)
        if isinstance(spec, ast.MapType):
            key, value = self.type_of(spec.key, scope, depth + 1), self.type_of(spec.value, scope, depth + 1)
            bound = self._positive(spec.bound, scope, "map bound") if spec.bound is not None else None
            if key is None or value is None:
                return None
            k = self._alias(key)
            if not (isinstance(k, ir.String) or (isinstance(k, ir.Primitive) and k.name in ir.INTEGER_RANGES)):
                self.sink.error("RG0207", f"map key must be an integer or string type, not '{key}'", spec.key.loc)
                return None
            return ir.Map(key, value, bound)
        if isinstance(spec, ast.FixedType):
            if spec.digits is None or spec.scale is None:
                return ir.Fixed(31, 0)
            digits = self._positive(spec.digits, scope, "fixed digits")
            scale = self.evaluator.evaluate(spec.scale, Target("int", "uint16"), self._name_value(scope))
            if digits is None or scale is None:
                return None
            assert isinstance(scale, int)  # the uint16 target converts or fails
            if digits > 31 or scale > digits:
                self.sink.error("RG0404", f"fixed<{digits}, {scale}> needs 1 <= digits <= 31 and scale <= digits",
                                spec.loc)
                return None
            return ir.Fixed(digits, scale)
        return None

    def _declared(self, spec: ast.TypeSpec, decl: ast.Declarator, scope: tuple[str, ...]) -> ir.Type | None:
        t = self.type_of(spec, scope)
        if not decl.dims:
            return t
        dims = [self._positive(e, scope, "array size") for e in decl.dims]
        sizes = tuple(d for d in dims if d is not None)
        if t is None or len(sizes) != len(dims):
            return None
        return ir.Array(t, sizes)

    # == declarations ========================================================================
    def declaration(self, sym: _Sym) -> ir.Declaration | None:
        """The resolved declaration for a symbol, resolving it (once) on demand."""
        if sym.scoped in self.done:
            return self.done[sym.scoped]
        if sym.scoped in self.busy:
            what = "inheritance" if sym.kind in ("struct", "bitset") else "definition"
            chain = list(self.busy)[list(self.busy).index(sym.scoped):] + [sym.scoped]
            self.sink.error("RG0302", f"circular {what}: {' -> '.join(chain)}", sym.loc)
            self.done[sym.scoped] = None
            return None
        self.busy[sym.scoped] = None
        try:
            resolver = _RESOLVERS.get(sym.kind)
            result = resolver(self, sym) if resolver else None
        except RecursionError:
            self.done[sym.scoped] = None  # the whole chain fails, and is reported once
            if len(self.busy) > 1:
                raise  # unwind to the outermost declaration, which reports it
            if not self.too_deep:
                self.sink.error("RG0201", f"'{sym.scoped}' is nested too deeply to resolve", sym.loc,
                                "it depends on a very long chain of declarations or a very deep expression")
            self.too_deep = True
            result = None
        finally:
            self.busy.pop(sym.scoped, None)
        self.done.setdefault(sym.scoped, result)
        return self.done[sym.scoped]

    def _anns(self, anns, where: str, scope, value_target=None) -> Checked:
        return self.annotations.check(anns, where, self._name_value(scope), value_target)

    @staticmethod
    def _extensibility(checked: Checked) -> ir.Extensibility:
        names: tuple[ir.Extensibility, ...] = ("final", "appendable", "mutable")
        for name in names:
            if checked.has(name):
                return name
        # @extensibility(FINAL|APPENDABLE|MUTABLE): the checker allows only these words
        ext = str(checked.get("extensibility", default="FINAL")).lower()
        return next((n for n in names if n == ext), "final")

    @staticmethod
    def _autoid(checked: Checked) -> ir.AutoId:
        return "HASH" if checked.get("autoid") == "HASH" else "SEQUENTIAL"

    def _member(self, md: ast.MemberDecl, decl: ast.Declarator, scope, ids: MemberIds,
                where: str = "member") -> ir.Member | None:
        t = self._declared(md.type, decl, scope)
        if t is None:
            return None
        if not md.annotations:  # the common case (its sequential id inline: thousands of members)
            mid = ids.take(decl.name, None, None) if ids.hashed else ids.next
            ids.next = mid + 1
            return ir.Member(decl.name, t, decl.loc, (), md.key_comment, False, False, None, None,
                             mid & ir.MEMBER_ID_MASK)
        checked = self._anns(md.annotations, where, scope, lambda: self._target(t))
        key = md.key_comment or bool(checked.get("key", default=False))
        if md.key_comment and checked.has("optional"):
            self.sink.error("RG0504", "a key member cannot be @optional", decl.loc)
        explicit = checked.integer("id")
        hashid = str(checked.get("hashid")) if checked.has("hashid") else None
        try:
            member_id = ids.take(decl.name, explicit, hashid)
        except UnicodeEncodeError:  # a lone surrogate (\ud800 escape): no UTF-8 bytes to hash
            self.sink.error("RG0502", f"'@hashid' of member '{decl.name}' is not valid Unicode text "
                            "(a lone surrogate)", decl.loc, "hash ids are computed from the UTF-8 bytes")
            member_id = ids.take(decl.name, ids.next, None)
        return ir.Member(decl.name, t, decl.loc, checked.annotations, key,
                         bool(checked.get("optional", default=False)),
                         bool(checked.get("external", default=False)),
                         explicit, checked.get("default"), member_id)

    def _check_member_names(self, members: list[ir.Member], inherited: tuple[ir.Member, ...], owner: str) -> list[ir.Member]:
        seen: dict[str, ir.Member] = {m.name: m for m in inherited}
        lowered = {m.name.lower(): m for m in inherited}
        out = []
        for m in members:
            if m.name in seen:
                first = seen[m.name]
                origin = "inherited from a base" if first in inherited else f"first declared at {first.loc}"
                self.sink.error("RG0205", f"duplicate member '{m.name}' in '{owner}'", m.loc, origin)
                continue
            if m.name.lower() in lowered:
                self.sink.warning("RG0312", f"member '{m.name}' differs only in case from '{lowered[m.name.lower()].name}'",
                                  m.loc, "IDL 4 rejects this; RTI's dialect accepts it")
            seen[m.name] = m
            lowered[m.name.lower()] = m
            out.append(m)
        return out

    def _resolve_struct(self, sym: _Sym) -> ir.Struct | None:
        d = _decl(sym, ast.StructDecl)
        outer = sym.scope[:-1]
        base_name = None
        inherited: tuple[ir.Member, ...] = ()
        if d.base is not None:
            bsym = self.lookup(d.base, sym.scope)
            if bsym is None:
                self._unknown(d.base, sym.scope, "base type", frozenset({"struct", "typedef", "forward"}))
            else:
                base = self.declaration(bsym)
                if isinstance(base, ir.Typedef):
                    target = self._alias(base.type)
                    base = self._get(target.name) if isinstance(target, ir.TypeRef) else None
                if isinstance(base, ir.Struct):
                    base_name = base.scoped_name
                    inherited = ir.flatten(base, self.done.get)
                elif bsym.kind == "forward":
                    self.sink.error("RG0309", f"'{bsym.scoped}' is declared but never defined", d.base.loc,
                                    f"define it after its forward declaration at {bsym.loc}")
                elif sym.scoped not in self.done and not (base is None and bsym.kind == "struct"):
                    # (a struct that resolves to nothing is part of a cycle, already reported)
                    kind = bsym.kind if base is None else base.kind
                    self.sink.error("RG0301", f"base of '{sym.scoped}' must be a struct or valuetype, "
                                    f"but '{d.base}' is {_article(kind)}", d.base.loc)
        checked = self._anns(d.annotations, "struct", outer)
        autoid = self._autoid(checked)
        ids = MemberIds(autoid, inherited)
        members: list[ir.Member] = []
        for md in d.members:
            for decl in md.declarators:
                m = self._member(md, decl, sym.scope, ids)
                if m is not None:
                    members.append(m)
        members = self._check_member_names(members, inherited, sym.scoped)
        return ir.Struct(d.name, sym.scoped, d.loc, tuple(members), base_name, checked.annotations,
                         self._extensibility(checked), (), cast(ir.Origin, d.origin),
                         bool(checked.get("nested", default=False)),
                         autoid)

    def _resolve_union(self, sym: _Sym) -> ir.Union | None:
        d = _decl(sym, ast.UnionDecl)
        outer = sym.scope[:-1]
        disc = self.type_of(d.discriminator, outer)
        if disc is None:
            return None
        real = self._alias(disc)
        ok = (isinstance(real, ir.Primitive) and real.name in _DISCRIMINATOR_PRIMITIVES) or \
             (isinstance(real, ir.TypeRef) and real.kind == "enum")
        if not ok:
            self.sink.error("RG0307", f"union discriminator must be an integer, char, boolean, octet or enum type, "
                            f"not '{disc}'", d.discriminator.loc)
            return None
        target = self._target(disc)
        disc_checked = self._anns(d.disc_annotations, "discriminator", outer)
        checked = self._anns(d.annotations, "union", outer)
        autoid = self._autoid(checked)
        ids = MemberIds(autoid)
        cases: list[ir.UnionCase] = []
        labels_seen: dict[object, SourceLoc] = {}
        default_at: SourceLoc | None = None
        for case in d.cases:
            labels: list[ir.Label] = []
            is_default = False
            for expr in case.labels:
                if expr is None:
                    if default_at is not None:
                        self.sink.error("RG0306", f"union '{sym.scoped}' has more than one default label",
                                        case.loc, f"first default at {default_at}")
                    default_at, is_default = case.loc, True
                    continue
                value = self.evaluator.evaluate(expr, target, self._name_value(outer))
                if value is None:
                    continue
                # a discriminator's target is an integer, char, boolean or enum
                assert not isinstance(value, (float, Decimal)), value
                keyed = value.value if isinstance(value, ir.EnumValue) else value
                if keyed in labels_seen:
                    self.sink.error("RG0304", f"duplicate case label {value} in union '{sym.scoped}'", expr.loc,
                                    f"first used at {labels_seen[keyed]}")
                    continue
                labels_seen[keyed] = expr.loc
                labels.append(value)
            m = self._member(case.member, case.member.declarators[0], outer, ids)
            if m is not None:
                cases.append(ir.UnionCase(tuple(labels), is_default, m))
        kept = {id(m) for m in self._check_member_names([c.member for c in cases], (), sym.scoped)}
        cases = [c for c in cases if id(c.member) in kept]  # (by identity: `in` a list was quadratic)
        enum = self._get(real.name) if isinstance(real, ir.TypeRef) else None
        default = discriminator_default(real, enum if isinstance(enum, ir.Enum) else None)
        return ir.Union(d.name, sym.scoped, d.loc, disc, tuple(cases), checked.annotations,
                        self._extensibility(checked), bool(disc_checked.get("key", default=False)),
                        bool(checked.get("nested", default=False)), autoid, default,
                        union_default(tuple(cases), default))

    def _resolve_enum(self, sym: _Sym) -> ir.Enum | None:
        d = _decl(sym, ast.EnumDecl)
        checked = self._anns(d.annotations, "enum", sym.scope)
        bit_bound = checked.integer("bit_bound", default=32) or 0
        if not 1 <= bit_bound <= 32:
            self.sink.error("RG0502", f"@bit_bound of an enum must be 1..32, not {bit_bound}", d.loc)
            bit_bound = 32
        out: list[ir.Enumerator] = []
        names: dict[str, SourceLoc] = {}
        values: dict[int, str] = {}
        next_value = 0
        for e in d.enumerators:
            eck = self._anns(e.annotations, "enumerator", sym.scope, lambda: Target("int", "int32"))
            value: ir.ConstValue | None = next_value
            if e.value is not None:
                value = self.evaluator.evaluate(e.value, Target("int", "int32"), self._name_value(sym.scope))
            elif eck.has("value"):
                value = eck.get("value")
            if value is None:
                continue
            assert isinstance(value, int)  # evaluated against int32 (a literal or @value)
            if e.name in names:
                self.sink.error("RG0308", f"duplicate enumerator '{e.name}' in enum '{sym.scoped}'", e.loc,
                                f"first declared at {names[e.name]}")
                continue
            if value in values:
                self.sink.error("RG0308", f"enumerators '{values[value]}' and '{e.name}' have the same value {value}",
                                e.loc)
                continue
            names[e.name], values[value] = e.loc, e.name
            out.append(ir.Enumerator(e.name, value, e.loc, eck.annotations))
            next_value = value + 1
        default, declared = enum_default(tuple(out))
        return ir.Enum(d.name, sym.scoped, d.loc, tuple(out), bit_bound, checked.annotations,
                       self._extensibility(checked), default, declared)

    def _resolve_bitmask(self, sym: _Sym) -> ir.Bitmask | None:
        d = _decl(sym, ast.BitmaskDecl)
        checked = self._anns(d.annotations, "bitmask", sym.scope)
        bit_bound = checked.integer("bit_bound", default=32) or 0
        if not 1 <= bit_bound <= 64:
            self.sink.error("RG0502", f"@bit_bound of a bitmask must be 1..64, not {bit_bound}", d.loc)
            bit_bound = 32
        out: list[ir.BitValue] = []
        used: dict[int, str] = {}
        names: set[str] = set()
        pos = 0
        for v in d.values:
            vck = self._anns(v.annotations, "bit_value", sym.scope)
            pos = vck.integer("position", default=pos) or 0
            if v.name in names:
                self.sink.error("RG0308", f"duplicate bit value '{v.name}' in bitmask '{sym.scoped}'", v.loc)
            elif pos >= bit_bound:
                self.sink.error("RG0402", f"bit position {pos} of '{v.name}' is outside the bit bound {bit_bound}", v.loc)
            elif pos in used:
                self.sink.error("RG0308", f"bit values '{used[pos]}' and '{v.name}' share position {pos}", v.loc)
            else:
                out.append(ir.BitValue(v.name, pos, v.loc, vck.annotations))
                used[pos] = v.name
            names.add(v.name)
            pos += 1
        return ir.Bitmask(d.name, sym.scoped, d.loc, tuple(out), bit_bound, checked.annotations)

    def _resolve_bitset(self, sym: _Sym) -> ir.Bitset | None:
        d = _decl(sym, ast.BitsetDecl)
        base_name, total = None, 0
        if d.base is not None:
            bsym = self.lookup(d.base, sym.scope)
            base = self.declaration(bsym) if bsym else None
            if bsym is None:
                self._unknown(d.base, sym.scope, "base bitset", frozenset({"bitset"}))
            elif base is None and bsym.kind == "bitset":
                pass  # part of an inheritance cycle, already reported
            elif not isinstance(base, ir.Bitset):
                self.sink.error("RG0301", f"base of bitset '{sym.scoped}' must be a bitset", d.base.loc)
            else:
                base_name, total = base.scoped_name, sum(f.width for f in base.fields)
        fields: list[ir.Bitfield] = []
        for f in d.fields:
            width = self._positive(f.width, sym.scope, "bitfield width")
            if width is None:
                continue
            if width > 64:
                self.sink.error("RG0402", f"bitfield width {width} exceeds 64", f.width.loc)
                continue
            ftype = self.type_of(f.type, sym.scope) if f.type else ir.Primitive(_bitfield_holder(width))
            if not isinstance(ftype, ir.Primitive):
                continue
            for name in f.names or (None,):
                fields.append(ir.Bitfield(name, width, ftype, f.loc))
            total += width * max(1, len(f.names))
        if total > 64:
            self.sink.error("RG0402", f"bitset '{sym.scoped}' holds {total} bits; at most 64 fit", d.loc)
        checked = self._anns(d.annotations, "bitset", sym.scope)
        return ir.Bitset(d.name, sym.scoped, d.loc, tuple(fields), base_name, checked.annotations)

    def _resolve_typedef(self, sym: _Sym) -> ir.Typedef | None:
        d = _decl(sym, ast.TypedefDecl)
        decl = sym.extra
        assert isinstance(decl, ast.Declarator)
        t = self._declared(d.type, decl, sym.scope)
        if t is None:
            return None
        checked = self._anns(d.annotations, "typedef", sym.scope)
        return ir.Typedef(decl.name, sym.scoped, decl.loc, t, checked.annotations)

    def _resolve_const(self, sym: _Sym) -> ir.Const | None:
        d = _decl(sym, ast.ConstDecl)
        t = self.type_of(d.type, sym.scope)
        if t is None:
            return None
        target = self._target(t)
        real = self._alias(t)
        if target.category == "any":
            self.sink.error("RG0401", f"a constant cannot have type '{real}'", d.type.loc,
                            "constants are integers, floats, fixed, chars, strings, booleans, octets or enums")
            return None
        value = self.evaluator.evaluate(d.value, target, self._name_value(sym.scope), const_decl=True)
        if value is None:
            return None
        checked = self._anns(d.annotations, "const", sym.scope)
        return ir.Const(d.name, sym.scoped, d.loc, t, value, checked.annotations)

    def _resolve_native(self, sym: _Sym) -> ir.Native:
        d = _decl(sym, ast.NativeDecl)
        return ir.Native(d.name, sym.scoped, d.loc)

    # == whole specification =================================================================
    def run(self, spec: ast.Specification) -> ir.Model:
        self._collect(spec.definitions, ())
        for sym in list(self.syms.values()):
            if sym.kind == "forward":
                continue
            self.declaration(sym)
        decls = [d for d in self.done.values() if d is not None]
        # Declarations in source order (the symbol table's order), then keys and order.
        order = {s: i for i, s in enumerate(self.syms)}
        decls.sort(key=lambda d: order.get(d.scoped_name, 0))
        decls = apply_keylists(decls, self.pragmas, self, self.sink)
        decls = compute_keys(decls, self.sink)
        check_recursion(decls, self.sink)
        ordered = dependency_order(decls)
        return ir.Model(tuple(self.modules.values()), tuple(ordered), spec.files)


# What resolves each kind of symbol (enumerators and forward declarations: nothing). Plain
# functions, not methods bound in the instance: a resolver referring to itself would be a
# reference cycle, and the syntax tree it holds would wait for the cyclic collector.
_RESOLVERS: dict[str, Callable[[Resolver, _Sym], ir.Declaration | None]] = {
    "struct": Resolver._resolve_struct, "union": Resolver._resolve_union, "enum": Resolver._resolve_enum,
    "bitmask": Resolver._resolve_bitmask, "bitset": Resolver._resolve_bitset,
    "typedef": Resolver._resolve_typedef, "const": Resolver._resolve_const, "native": Resolver._resolve_native,
}


def _matches_forward(sym: _Sym, forward_kind: str) -> bool:
    if sym.kind == "union":
        return forward_kind == "union"
    if sym.kind == "struct":
        origin = getattr(sym.decl, "origin", "struct")
        return forward_kind == origin
    return False


def _category(target: Target) -> str:
    return {"int": "int", "float": "float", "fixed": "fixed", "char": "char", "string": "string",
            "bool": "bool", "enum": "enum"}.get(target.category, "int")


def _article(kind: str) -> str:
    return ("an " if kind[0] in "aeiou" else "a ") + kind


def _bitfield_holder(width: int) -> str:
    if width == 1:
        return "boolean"
    for bits, name in ((8, "uint8"), (16, "uint16"), (32, "uint32")):
        if width <= bits:
            return name
    return "uint64"


def resolve(spec: ast.Specification, sink: DiagnosticSink) -> ir.Model:
    try:
        return Resolver(sink).run(spec)
    except RecursionError:  # e.g. thousands of nested modules
        sink.error("RG0201", "input is nested too deeply", SourceLoc(spec.files[0] if spec.files else "<input>", 1, 1))
        return ir.Model((), (), spec.files)

