"""IR -> view objects for the C++ templates: every name, type spelling and statement decided.

One header `types.hpp` holds every declaration in the model's dependency order, each IDL
module a C++ namespace (`rapid::ext::arc`); `types.cpp` the XCDR1 encode/decode functions;
`topics.hpp` a Fast DDS TopicDataType per struct. Structs are flattened like the Python
classes (base members first, docs/cpp-backend.md). Templates only print.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from rapidgen.backends import base
from rapidgen.backends.cpp import namer
from rapidgen.backends.cpp.typemap import ENUM_TYPES, TypeMap, enum_size
from rapidgen.backends.escape import cpp_str
from rapidgen.backends.typewalk import Unsupported, spelled_members
from rapidgen.diagnostics import SourceLoc
from rapidgen.model import ir, wire

# The initial payload size Fast DDS preallocates per sample (it grows as needed): the
# type's bound when small, else this.
INITIAL_PAYLOAD = 64 * 1024


class UnsupportedInput(base.UnsupportedInput):
    """The model uses what the cpp target cannot express."""

    CODE = "RG1702"
    TARGET = "cpp"


@dataclass
class MemberView:
    name: str
    type: str
    init: str
    wire: str  # the IDL name, in comments and error messages


@dataclass
class CaseView:
    index: int  # variant index (0: no member)
    name: str
    type: str
    init: str  # value of a fresh branch
    cond: str  # C++ condition on `d` selecting it ("" for the default case)
    select: str  # a discriminator value selecting it
    encode: list[str]
    decode: list[str]


@dataclass
class DeclView:
    kind: str  # struct, union, enum, typedef, const
    name: str
    qualified: str
    doc: str
    type: str = ""  # typedef target, const type, enum underlying or union discriminator type
    value: str = ""  # const value
    members: list[MemberView] = field(default_factory=list)
    enumerators: list[tuple[str, int]] = field(default_factory=list)
    cases: list[CaseView] = field(default_factory=list)
    default_disc: str = ""
    default_index: int = 0
    encode: list[str] = field(default_factory=list)
    decode: list[str] = field(default_factory=list)
    key: list[str] = field(default_factory=list)
    keyed: bool = False
    helper: str = ""  # enums: name of the validating function in types.cpp
    scoped: str = ""  # the IDL scoped name


@dataclass
class BlockView:
    namespace: str  # "rapid::ext" or "" (global scope)
    decls: list[DeclView]


@dataclass
class TopicView:
    qualified: str
    type_name: str  # DDS type name literal
    alias: str  # the PubSubType alias in the type's namespace
    namespace: str
    keyed: bool
    key_max: int
    initial: int


@dataclass
class PackageView:
    package: str
    guard: str  # include-guard prefix
    header: str
    source: str
    blocks: list[BlockView]
    topics: list[TopicView]
    enums: list[DeclView]


class Builder:
    def __init__(self, model: ir.Model, package: str) -> None:
        self.model = model
        self.package = package
        self.problems: list[tuple[str, SourceLoc | None]] = []
        self.ns_scopes: dict[tuple[str, ...], namer.Scope] = {(): namer.Scope("global", namer.NAMESPACE_RESERVED)}
        self.ns_names: dict[tuple[str, ...], tuple[str, ...]] = {(): ()}
        self.names: dict[str, str] = {}
        self.enum_names: dict[str, dict[str, str]] = {}
        self.ns_scopes[()].claim(package, "the package's own namespace (asset.hpp)")
        for d in model.declarations:  # modules first, so declarations step aside for them
            path = tuple(d.scoped_name.split("::")[:-1])
            self._namespace(path)
        for d in model.declarations:
            path = tuple(d.scoped_name.split("::")[:-1])
            self.names[d.scoped_name] = self.ns_scopes[path].claim(d.name, d.scoped_name)
            if isinstance(d, ir.Enum):
                scope = namer.Scope(f"enum {d.scoped_name}")
                self.enum_names[d.scoped_name] = {e.name: scope.claim(e.name, e.name) for e in d.enumerators}
        self.types = TypeMap(model, self.qualified)
        self.types.enumerator = lambda e, name: self.enum_names[e.scoped_name][name]  # type: ignore[method-assign]
        self.enum_helpers: dict[str, str] = {}

    def _namespace(self, path: tuple[str, ...]) -> tuple[str, ...]:
        if path not in self.ns_names:
            parent = self._namespace(path[:-1])
            name = self.ns_scopes[path[:-1]].claim(path[-1], "module " + "::".join(path))
            self.ns_names[path] = parent + (name,)
            self.ns_scopes[path] = namer.Scope("namespace " + "::".join(path), namer.NAMESPACE_RESERVED)
        return self.ns_names[path]

    def namespace_of(self, scoped: str) -> str:
        return "::".join(self.ns_names[tuple(scoped.split("::")[:-1])])

    def qualified(self, scoped: str) -> str:
        ns = self.namespace_of(scoped)
        return f"::{ns}::{self.names[scoped]}" if ns else f"::{self.names[scoped]}"

    def enum_check(self, e: ir.Enum) -> str:
        return self.enum_helpers.setdefault(e.scoped_name, f"enum_{len(self.enum_helpers)}")

    # -- the package --------------------------------------------------------------------
    def build(self, header: str, source: str) -> PackageView:
        blocks: list[BlockView] = []
        topics: list[TopicView] = []
        enums: list[DeclView] = []
        for d in self.model.declarations:
            try:
                view = self.declaration(d)
            except Unsupported as exc:
                self.problems.append((str(exc), exc.loc or d.loc))
                continue
            ns = self.namespace_of(d.scoped_name)
            if not blocks or blocks[-1].namespace != ns:
                blocks.append(BlockView(ns, []))
            blocks[-1].decls.append(view)
            if view.kind == "enum":
                enums.append(view)
            if isinstance(d, ir.Struct):
                alias = self.ns_scopes[tuple(d.scoped_name.split("::")[:-1])].claim(
                    d.name + "PubSubType", "topic type of " + d.scoped_name)
                key_max = self._key_max(d)
                size = self.types.max_size(ir.TypeRef(d.scoped_name, "struct")) + 4
                topics.append(TopicView(view.qualified, cpp_str(d.scoped_name), alias, ns, view.keyed,
                                        key_max, min(size, INITIAL_PAYLOAD)))
        if self.problems:
            raise UnsupportedInput(self.problems)
        for scope in self.ns_scopes.values():
            scope.check()
        for e in enums:
            e.helper = self.enum_helpers[e.scoped]
        return PackageView(self.package, self.package.upper(), header, source, blocks, topics, enums)

    def declaration(self, d: ir.Declaration) -> DeclView:
        name = self.names[d.scoped_name]
        q = self.qualified(d.scoped_name)
        if isinstance(d, ir.Typedef):
            return DeclView("typedef", name, q, f"IDL typedef {d.type} {d.scoped_name}",
                            type=self.types.cpp(d.type, d.loc))
        if isinstance(d, ir.Const):
            real = self.types.real(d.type)
            ctype = "std::string_view" if isinstance(real, ir.String) else self.types.cpp(d.type, d.loc)
            return DeclView("const", name, q, f"IDL const {d.scoped_name}", type=ctype,
                            value=self.types.literal(d.value, d.type, d.loc))
        if isinstance(d, ir.Enum):
            v = DeclView("enum", name, q, f"IDL enum {d.scoped_name}", type=ENUM_TYPES[enum_size(d)],
                         enumerators=[(self.enum_names[d.scoped_name][e.name], e.value) for e in d.enumerators])
            v.scoped = d.scoped_name
            self.enum_check(d)
            return v
        if isinstance(d, ir.Struct):
            return self.struct(d, name, q)
        if isinstance(d, ir.Union):
            return self.union(d, name, q)
        raise Unsupported(f"{d.kind} '{d.scoped_name}' is not supported by the cpp target", d.loc)

    def _check_ext(self, d: ir.Struct | ir.Union) -> None:
        # Fast DDS 2.9 writes XCDR1 only; appendable is laid out as final there, mutable is not.
        if d.extensibility == "mutable":
            raise Unsupported(f"@mutable {d.kind} '{d.scoped_name}' is not supported by the cpp target "
                              "(XCDR1 final and appendable only)", d.loc)

    def struct(self, s: ir.Struct, name: str, q: str) -> DeclView:
        self._check_ext(s)
        scope = namer.Scope(f"struct {s.scoped_name}", namer.RESERVED | {name})
        members, enc, dec = [], [], []
        for m, ctype in spelled_members(self.types, self.model, s, self.problems):
            cname = scope.claim(m.name, m.name)
            init = ("{" + self.types.literal(m.default, m.type, m.loc) + "}" if m.default is not None
                    else self.types.default(m.type, m.loc))
            members.append(MemberView(cname, ctype, init, m.name))
            what = f"{s.scoped_name}.{m.name}"
            enc += self.types.encode(m.type, f"v.{cname}", what)
            dec += self.types.decode(m.type, f"v.{cname}", what, self.enum_check)
        scope.check()
        doc = f"IDL {s.origin} {s.scoped_name}"
        if s.base:
            doc += f" : {s.base}, flattened (base members first)"
        doc += "." + (f" Key: {', '.join(s.keys)}." if s.keys else "")
        key = []
        for path in s.keys:
            key += self._key_path(s, path)
        return DeclView("struct", name, q, doc, members=members, encode=enc, decode=dec, key=key,
                        keyed=bool(s.keys))

    def _walk(self, s: ir.Struct, path: str) -> tuple[str, ir.Type, ir.Member]:
        """A key path ('hdr.srcName') as a C++ member expression and the leaf's type."""
        steps = self.model.key_path(s, path)
        if steps is None:
            raise Unsupported(f"key path '{path}' does not name a member", s.loc)
        member = steps[-1][1]
        return "v" + "".join("." + self._member_names(st)[m.name] for st, m in steps), member.type, member

    def _member_names(self, s: ir.Struct) -> dict[str, str]:
        scope = namer.Scope(f"struct {s.scoped_name}", namer.RESERVED | {self.names[s.scoped_name]})
        return {m.name: scope.claim(m.name, m.name) for m in self.model.all_members(s) if not m.optional}

    def _union_names(self, u: ir.Union) -> dict[str, str]:
        scope = namer.Scope(f"union {u.scoped_name}", namer.UNION_RESERVED | {self.names[u.scoped_name]})
        return {c.member.name: scope.claim(c.member.name, c.member.name) for c in u.cases}

    def _key_path(self, s: ir.Struct, path: str) -> list[str]:
        expr, t, _ = self._walk(s, path)
        return self.types.encode(t, expr, f"{s.scoped_name} key {path}")

    def _key_max(self, s: ir.Struct) -> int:
        return wire.key_max_size(self.model, [self._walk(s, path)[1] for path in s.keys])

    def union(self, u: ir.Union, name: str, q: str) -> DeclView:
        self._check_ext(u)
        disc_real = self.types.real(u.discriminator)
        disc_type = self.types.cpp(u.discriminator, u.loc)
        scope = namer.Scope(f"union {u.scoped_name}", namer.UNION_RESERVED | {name})
        used = [lab for c in u.cases for lab in c.labels]
        cases = []
        for i, c in enumerate(u.cases, start=1):
            m = c.member
            try:
                ctype = self.types.cpp(m.type, m.loc)
            except Unsupported as exc:
                self.problems.append((str(exc), exc.loc or m.loc))
                continue
            cname = scope.claim(m.name, m.name)
            cond = " || ".join(f"d == {self.types.literal(lab, u.discriminator, u.loc)}" for lab in c.labels)
            select = (self.types.literal(c.labels[0], u.discriminator, u.loc) if c.labels
                      else self._unlabelled(u, disc_real, used))
            what = f"{u.scoped_name}.{m.name}"
            cases.append(CaseView(i, cname, ctype, self.types.default(m.type, m.loc), "" if c.is_default else cond,
                                  select, self.types.encode(m.type, "x", what),
                                  self.types.decode(m.type, "x", what, self.enum_check)))
        scope.check()
        d = self.types.decl(disc_real)
        if isinstance(d, ir.Enum):
            self.enum_check(d)
        disc_enc = self.types.encode(u.discriminator, "v._d()", f"{u.scoped_name} discriminator")
        disc_dec = self.types.decode(u.discriminator, "d", f"{u.scoped_name} discriminator", self.enum_check)
        return DeclView("union", name, q, f"IDL union {u.scoped_name} switch ({u.discriminator}).",
                        type=disc_type, cases=cases,
                        default_disc=self.types.literal(u.default_discriminator, u.discriminator, u.loc),
                        default_index=(u.default_case + 1) if u.default_case is not None else 0,
                        encode=disc_enc, decode=disc_dec)

    def _unlabelled(self, u: ir.Union, disc: ir.Type, used: list[ir.Label]) -> str:
        """A discriminator value no label names (for the default case's setter)."""
        taken = {ir.label_key(lab) for lab in used}
        d = self.types.decl(disc)
        if isinstance(d, ir.Enum):
            for e in d.enumerators:
                if (False, e.value) not in taken:
                    return self.types.literal(ir.EnumValue(d.scoped_name, e.name, e.value), disc, u.loc)
            return self.types.literal(u.default_discriminator, u.discriminator, u.loc)
        if isinstance(disc, ir.Primitive) and disc.name == "boolean":
            return "false" if (True, False) not in taken else "true"
        n = 0
        while (False, n) in taken or (disc.name == "char8" and (False, chr(n)) in taken):  # type: ignore[union-attr]
            n += 1
        return self.types.literal(n, disc, u.loc)
