"""IR -> view objects for the Rust templates: every name, type spelling and expression decided.

Each IDL module is a Rust module in its own file (`rapid::ext` -> src/rapid/ext.rs), the
crate root holds the global scope, the runtime (`cdr`) and `visit_types`. Structs are
flattened like the Python and C++ classes (base members first); unions are Rust enums
whose variants carry the discriminator when it is not implied (several labels, the
default case, no member). Templates only print.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

from rapidgen.backends import base
from rapidgen.backends.rust.typemap import rust_str
from rapidgen.backends.rust import namer
from rapidgen.backends.rust.typemap import ENUM_REPR, TypeMap, enum_size
from rapidgen.backends.typewalk import Unsupported, spelled_members
from rapidgen.diagnostics import SourceLoc
from rapidgen.model import ir, wire

DEFAULT = "::core::default::Default::default()"


class UnsupportedInput(base.UnsupportedInput):
    """The model uses what the rust target cannot express."""

    CODE = "RG1703"
    TARGET = "rust"


@dataclass
class MemberView:
    name: str
    type: str
    wire: str  # the IDL name
    default: str  # expression for a hand-written Default
    decode: str
    serde: str = ""  # the member's #[serde(...)] arguments ("" none)
    decode_into: str = ""  # statement reading the member over self's (capacity reused)


@dataclass
class ArmView:
    pattern: str  # decode match pattern ("_" for the rest)
    build: str  # decode arm value
    head: str  # encode match pattern
    check: str  # encode: a condition refusing a carried discriminator ("" none)
    variant: str  # the variant's name (in the refusal's message)
    encode: list[str]  # encode statements
    size_head: str  # size match pattern
    size: str  # size statement (the branch's value; the discriminator's is the same for all)
    into_head: str = ""  # decode_into: the pattern binding the variant's value as `x` ("" none)
    into: str = ""  # decode_into: statements reading the branch over `x` (capacity reused)


@dataclass
class DeclView:
    kind: str  # struct, union, enum, typedef, const
    name: str
    doc: str
    type_name: str = ""  # the DDS type name literal
    type: str = ""  # typedef target, const type, enum repr, union discriminator type
    value: str = ""  # const value, union default expression
    members: list[MemberView] = field(default_factory=list)
    derive_default: bool = True
    encode: list[str] = field(default_factory=list)
    size: list[str] = field(default_factory=list)  # struct: statements sizing the members
    variants: list[tuple[str, int, str]] = field(default_factory=list)  # enum: name, value, IDL name
    default_variant: str = ""
    variant_types: list[tuple[str, str]] = field(default_factory=list)  # union: name, tuple fields
    serde: str = ""  # the type's #[serde(...)] arguments ("" none)
    variant_serde: dict[str, str] = field(default_factory=dict)  # enum/union variant -> #[serde(...)] arguments
    arms: list[ArmView] = field(default_factory=list)
    disc_decode: str = ""
    allow_unreachable: bool = False
    key: list[str] = field(default_factory=list)  # struct: statements writing the key members
    key_max: int = 0  # struct: KEY_MAX_SIZE
    transcode: list[str] = field(default_factory=list)  # struct: statements re-writing the key members


@dataclass
class ModuleView:
    path: str  # from the crate root ("" for the root)
    file: str
    doc: str
    decls: list[DeclView] = field(default_factory=list)
    children: list[str] = field(default_factory=list)


@dataclass
class CrateView:
    crate: str
    header: str
    source: str
    modules: list[ModuleView]
    types: list[str]  # paths of the structs and unions, for visit_types
    serde_arrays: bool = False  # a member needs src/serde_arrays.rs (an array longer than 32)


class Builder:
    def __init__(self, model: ir.Model) -> None:
        self.model = model
        self.problems: list[tuple[str, SourceLoc | None]] = []
        self.scopes: dict[tuple[str, ...], namer.Scope] = {(): namer.Scope("crate root", namer.ROOT_RESERVED)}
        self.mod_names: dict[tuple[str, ...], tuple[str, ...]] = {(): ()}
        self.names: dict[str, str] = {}
        self.enum_names: dict[str, dict[str, str]] = {}
        for d in model.declarations:  # modules first, so declarations step aside for them
            self._module(tuple(d.scoped_name.split("::")[:-1]))
        for d in model.declarations:
            scope = self.scopes[tuple(d.scoped_name.split("::")[:-1])]
            pref = namer.upper(d.name) if isinstance(d, ir.Const) else namer.camel(d.name)
            self.names[d.scoped_name] = scope.claim(pref, d.scoped_name)
            if isinstance(d, ir.Enum):
                es = namer.Scope(f"enum {d.scoped_name}")
                self.enum_names[d.scoped_name] = {e.name: es.claim(namer.camel(e.name), e.name)
                                                  for e in d.enumerators}
        self.types = TypeMap(model, self.path)
        self.types.variant = lambda e, n: self.enum_names[e.scoped_name][n]
        self.fields: dict[str, dict[str, str]] = {}  # struct -> IDL member name -> field
        self.variants: dict[str, dict[int, tuple[str, bool]]] = {}  # union -> case index -> (variant, carries)
        self.serde_arrays = False

    def _serde(self, rust: str, wire: str, t: ir.Type | None = None) -> str:
        """#[serde(...)] arguments: the IDL name where Rust's differs (JSON and the like show
        the names the IDL, the Python bindings and the vectors use), the helper for long arrays."""
        args = [] if rust == wire else [f"rename = {rust_str(wire)}"]
        with_ = self.types.serde_with(t) if t is not None else None
        if with_:
            self.serde_arrays = True
            args.append(f'with = "{with_}"')
        return ", ".join(args)

    def _module(self, path: tuple[str, ...]) -> tuple[str, ...]:
        if path not in self.mod_names:
            parent = self._module(path[:-1])
            name = self.scopes[path[:-1]].claim(namer.snake(path[-1]), "module " + "::".join(path))
            self.mod_names[path] = parent + (name,)
            # a child named like its parent is clippy's module_inception
            self.scopes[path] = namer.Scope("module " + "::".join(path), {name})
        return self.mod_names[path]

    def module_of(self, scoped: str) -> tuple[str, ...]:
        return self.mod_names[tuple(scoped.split("::")[:-1])]

    def path(self, scoped: str) -> str:
        return "::".join(("crate",) + self.module_of(scoped) + (self.names[scoped],))

    # -- the crate ----------------------------------------------------------------------
    def build(self, crate: str, header: str, source: str) -> CrateView:
        modules = {p: ModuleView("::".join(p), "src/" + "/".join(p) + ".rs" if p else "src/lib.rs",
                                 "IDL module " + "::".join(idl) if idl else "")
                   for idl, p in self.mod_names.items()}
        for idl, p in self.mod_names.items():
            if p:
                modules[p[:-1]].children.append(p[-1])
        types: list[str] = []
        for d in self.model.declarations:
            try:
                view = self.declaration(d)
            except Unsupported as exc:
                self.problems.append((str(exc), exc.loc or d.loc))
                continue
            modules[self.module_of(d.scoped_name)].decls.append(view)
            if view.kind in ("struct", "union"):
                types.append(self.path(d.scoped_name))
        if self.problems:
            raise UnsupportedInput(self.problems)
        for scope in self.scopes.values():
            scope.check()
        return CrateView(crate, header, source, [modules[p] for p in sorted(modules)], types, self.serde_arrays)

    def declaration(self, d: ir.Declaration) -> DeclView:
        name = self.names[d.scoped_name]
        if isinstance(d, ir.Typedef):
            return DeclView("typedef", name, f"IDL typedef `{d.type} {d.scoped_name}`",
                            type=self.types.rust(d.type, d.loc))
        if isinstance(d, ir.Const):
            real = self.types.real(d.type)
            rtype = "&str" if isinstance(real, ir.String) and not real.wide else self.types.rust(d.type, d.loc)
            return DeclView("const", name, f"IDL const `{d.scoped_name}`", type=rtype,
                            value=self.types.literal(d.value, d.type))
        if isinstance(d, ir.Enum):
            names = self.enum_names[d.scoped_name]
            return DeclView("enum", name, f"IDL enum `{d.scoped_name}`", type_name=rust_str(d.scoped_name),
                            type=ENUM_REPR[enum_size(d)],
                            variants=[(names[e.name], e.value, e.name) for e in d.enumerators],
                            default_variant=names[d.default], serde=self._serde(name, d.name),
                            variant_serde={names[e.name]: self._serde(names[e.name], e.name) for e in d.enumerators})
        if isinstance(d, ir.Struct):
            return self.struct(d, name)
        if isinstance(d, ir.Union):
            return self.union(d, name)
        raise Unsupported(f"{d.kind} '{d.scoped_name}' is not supported by the rust target", d.loc)

    def _check_ext(self, d: ir.Struct | ir.Union) -> None:
        if d.extensibility == "mutable":
            raise Unsupported(f"@mutable {d.kind} '{d.scoped_name}' is not supported by the rust target "
                              "(XCDR1 final and appendable only)", d.loc)

    def struct(self, s: ir.Struct, name: str) -> DeclView:
        self._check_ext(s)
        scope = namer.Scope(f"struct {s.scoped_name}")
        members, enc, size = [], [], []
        derive = True
        for m, rtype in spelled_members(self.types, self.model, s, self.problems):
            rname = scope.claim(namer.snake(m.name), m.name)
            what = f"{s.scoped_name}.{m.name}"
            default = self.types.default(m.type)
            if m.default is not None:
                lit = self.types.literal(m.default, m.type)
                real = self.types.real(m.type)
                default = f"::std::string::String::from({lit})" if isinstance(real, ir.String) else lit
            derive = derive and default is None
            expr, fallible = self.types.encode(m.type, f"self.{rname}", what)
            enc.append(expr + ("?;" if fallible else ";"))
            size.append(self.types.size(m.type, f"self.{rname}"))
            members.append(MemberView(rname, rtype, m.name, default or DEFAULT, self.types.decode(m.type, what),
                                      self._serde(rname, m.name, m.type),
                                      self.types.decode_into(m.type, f"self.{rname}", what)))
        scope.check()
        self.fields[s.scoped_name] = {m.wire: m.name for m in members}
        doc = f"IDL {s.origin} `{s.scoped_name}`"
        if s.base:
            doc += f" : `{s.base}`, flattened (base members first)"
        doc += "." + (f" Key: `{', '.join(s.keys)}`." if s.keys else "")
        key, transcode, key_types = [], [], []
        for path in s.keys:
            place, t = self._walk(s, path)
            what = f"{s.scoped_name} key {path}"
            expr, fallible = self.types.encode(t, place, what)
            key.append(expr + ("?;" if fallible else ";"))
            # the key member read, then written in the writer's byte order
            k = self.types.var("k")
            expr, fallible = self.types.encode(t, k, what)
            again = f"{expr}.map_err(|e| r.error(format_args!(\"{{e}}\")))?;" if fallible else expr + ";"
            transcode.append(f"let {k} = {self.types.decode(t, what)};")
            transcode.append(again)
            key_types.append(t)
        return DeclView("struct", name, doc, type_name=rust_str(s.scoped_name), members=members,
                        derive_default=derive, encode=enc, size=size, key=key, key_max=wire.key_max_size(self.model, key_types),
                        transcode=transcode, serde=self._serde(name, s.name))

    def _walk(self, s: ir.Struct, path: str) -> tuple[str, ir.Type]:
        """A key path ('hdr.srcName') as a Rust place (`self.hdr.src_name`) and the leaf's type."""
        steps = self.model.key_path(s, path)
        if steps is None:
            raise Unsupported(f"key path '{path}' does not name a member", s.loc)
        return "self" + "".join("." + self.fields[st.scoped_name][m.name] for st, m in steps), steps[-1][1].type

    def union(self, u: ir.Union, name: str) -> DeclView:
        self._check_ext(u)
        t = self.types
        disc_type = t.rust(u.discriminator, u.loc)
        scope = namer.Scope(f"union {u.scoped_name}")
        everything = [lab for c in u.cases for lab in c.labels]
        covered = self._covers(u, everything)
        need_none = u.default_case is None and not covered
        if need_none:
            scope.claim(namer.NO_MEMBER, "(no member)")
        pats = {id(c): self._pattern(u, list(c.labels)) for c in u.cases}
        arms, types, variant_of = [], [], {}
        variant_serde: dict[str, str] = {}
        for c in u.cases:
            m = c.member
            try:
                mtype = t.rust(m.type, m.loc)
            except Unsupported as exc:
                self.problems.append((str(exc), exc.loc or m.loc))
                continue
            vname = scope.claim(namer.camel(m.name), m.name)
            variant_of[id(c)] = vname
            variant_serde[vname] = self._serde(vname, m.name)
            with_ = self._serde(vname, vname, m.type)  # a long array's helper on the branch's value
            if with_:
                mtype = f'#[cfg_attr(feature = "serde", serde({with_}))] {mtype}'
            what = f"{u.scoped_name}.{m.name}"
            body, fallible = t.encode(m.type, "*x", what)
            body += "?;" if fallible else ";"
            size = t.size(m.type, "*x")
            x = "x" if re.search(r"\bx\b", size) else "_"
            carries = c.is_default or len(c.labels) != 1
            # a branch holding heap (strings, sequences, structs) is read over the value the
            # variant holds when it is the same variant; a number is simply replaced
            in_place = not isinstance(t.real(m.type), ir.Primitive) and not isinstance(t.decl(t.real(m.type)), ir.Enum)
            into = t.decode_into(m.type, "*x", what) if in_place else ""
            self.variants.setdefault(u.scoped_name, {})[u.cases.index(c)] = (vname, carries)
            if carries:
                types.append((vname, f"{disc_type}, {mtype}"))
                others = self._pattern(u, [lab for o in u.cases if o is not c for lab in o.labels])
                check = (f"matches!(*d, {others})" if c.is_default and others
                         else "" if c.is_default else f"!matches!(*d, {pats[id(c)]})")
                arms.append(ArmView("_" if c.is_default else pats[id(c)], f"Self::{vname}(d, {t.decode(m.type, what)})",
                                    f"Self::{vname}(d, x)", check, vname, [self._disc_enc(u, "*d"), body],
                                    f"Self::{vname}(_, {x})", size, f"Self::{vname}(dx, x)" if into else "",
                                    f"*dx = d; {into}" if into else ""))
            else:
                types.append((vname, mtype))
                arms.append(ArmView(pats[id(c)], f"Self::{vname}({t.decode(m.type, what)})", f"Self::{vname}(x)", "",
                                    vname, [self._disc_enc(u, pats[id(c)]), body], f"Self::{vname}({x})", size,
                                    f"Self::{vname}(x)" if into else "", into))
        scope.check()
        if need_none:
            types.append((namer.NO_MEMBER, disc_type))
            arms.append(ArmView("_", f"Self::{namer.NO_MEMBER}(d)", f"Self::{namer.NO_MEMBER}(d)",
                                f"matches!(*d, {self._pattern(u, everything)})" if everything else "",
                                namer.NO_MEMBER, [self._disc_enc(u, "*d")], f"Self::{namer.NO_MEMBER}(_)", ""))
        arms.sort(key=lambda a: a.pattern == "_")  # the rest last
        if u.default_case is not None:
            c = u.cases[u.default_case]
            vname = variant_of.get(id(c), namer.NO_MEMBER)
            value = t.default(c.member.type) or DEFAULT
            carries = c.is_default or len(c.labels) != 1
            default = (f"Self::{vname}({t.literal(u.default_discriminator, u.discriminator)}, {value})" if carries
                       else f"Self::{vname}({value})")
        else:
            default = f"Self::{namer.NO_MEMBER}({t.literal(u.default_discriminator, u.discriminator)})"
        return DeclView("union", name, f"IDL union `{u.scoped_name}` switch (`{u.discriminator}`).",
                        type_name=rust_str(u.scoped_name), type=disc_type, value=default, variant_types=types,
                        arms=arms, size=[t.size(u.discriminator, "")], disc_decode=t.decode(u.discriminator, f"{u.scoped_name} discriminator"),
                        serde=self._serde(name, u.name), variant_serde=variant_serde,
                        allow_unreachable=covered and u.default_case is not None
                        and u.cases[u.default_case].is_default)

    def _pattern(self, u: ir.Union, labels: list[ir.Label]) -> str:
        """A match pattern of the labels; integer runs as ranges (`1..=3`, as clippy asks)."""
        ints = sorted({lab for lab in labels if isinstance(lab, int) and not isinstance(lab, bool)})
        if len(ints) != len(labels):
            return " | ".join(self.types.literal(lab, u.discriminator) for lab in labels)
        runs: list[list[int]] = []
        for v in ints:
            if runs and runs[-1][1] == v - 1:
                runs[-1][1] = v
            else:
                runs.append([v, v])
        lit = lambda v: self.types.literal(v, u.discriminator)  # noqa: E731
        return " | ".join(lit(a) if a == b else f"{lit(a)}..={lit(b)}" for a, b in runs)

    def _disc_enc(self, u: ir.Union, place: str) -> str:
        expr, fallible = self.types.encode(u.discriminator, place, f"{u.scoped_name} discriminator")
        return expr + ("?;" if fallible else ";")

    def _covers(self, u: ir.Union, labels: list[ir.Label]) -> bool:
        """Whether the labels name every value of the discriminator's type."""
        taken = {ir.label_key(lab) for lab in labels}
        real = self.types.real(u.discriminator)
        d = self.types.decl(real)
        if isinstance(d, ir.Enum):
            return all((False, e.value) in taken for e in d.enumerators)
        if isinstance(real, ir.Primitive) and real.name == "boolean":
            return len(taken) == 2
        if isinstance(real, ir.Primitive) and real.name in ("int8", "uint8", "octet", "char8"):
            return len(taken) >= 256
        return False


    # -- values (the asset's configs) ------------------------------------------------------
    def value(self, t: ir.Type, v: object) -> str:
        """A Rust expression of type t holding v, a value in the vectors' value form
        (docs/cdr-and-vectors.md); members left out take their defaults."""
        tm = self.types
        r = tm.real(t)
        if isinstance(r, ir.Primitive):
            return tm.literal(v, r)  # type: ignore[arg-type]
        if isinstance(r, ir.String):
            return f"::std::string::String::from({rust_str(str(v))})"
        if isinstance(r, (ir.Sequence, ir.Array)):
            items = list(v)  # type: ignore[call-overload]
            inner = ir.Array(r.element, r.dims[1:]) if isinstance(r, ir.Array) and len(r.dims) > 1 else r.element
            body = ", ".join(self.value(inner, x) for x in items)
            if isinstance(r, ir.Array):
                return f"[{body}]"
            return f"::std::vec![{body}]" if items else "::std::vec::Vec::new()"
        d = tm.decl(r)
        if isinstance(d, ir.Enum):
            return tm.literal(self._enum_value(d, v), r)
        if isinstance(d, ir.Struct):
            given = dict(v)  # type: ignore[call-overload]
            members = self.model.all_members(d)
            parts = [f"{self.fields[d.scoped_name][m.name]}: {self.value(m.type, given.pop(m.name))}"
                     for m in members if m.name in given]
            if given:
                raise ValueError(f"{d.scoped_name} has no member {sorted(given)[0]!r}")
            if len(parts) < len(members):
                parts.append("..::core::default::Default::default()")
            return f"{self.path(d.scoped_name)} {{ {', '.join(parts)} }}"
        if isinstance(d, ir.Union):
            return self._union_value(d, v)  # type: ignore[arg-type]
        raise ValueError(f"no Rust value of {t}")

    def _enum_value(self, e: ir.Enum, v: object) -> ir.EnumValue:
        for x in e.enumerators:
            if x.name == v or (isinstance(v, int) and not isinstance(v, bool) and x.value == v):
                return ir.EnumValue(e.scoped_name, x.name, x.value)
        raise ValueError(f"{v!r} is not an enumerator of {e.scoped_name}")

    def _union_value(self, u: ir.Union, v: dict) -> str:
        disc = v["discriminator"]
        dreal = self.types.real(u.discriminator)
        de = self.types.decl(dreal)
        if isinstance(de, ir.Enum):
            disc = self._enum_value(de, disc)
        key = ir.label_key(disc)
        dlit = self.types.literal(disc, u.discriminator)
        index = next((i for i, c in enumerate(u.cases) if any(ir.label_key(lab) == key for lab in c.labels)),
                     next((i for i, c in enumerate(u.cases) if c.is_default), None))
        if index is None:
            return f"{self.path(u.scoped_name)}::{namer.NO_MEMBER}({dlit})"
        vname, carries = self.variants[u.scoped_name][index]
        inner = self.value(u.cases[index].member.type, v["value"])
        return f"{self.path(u.scoped_name)}::{vname}({dlit + ', ' if carries else ''}{inner})"


def build(model: ir.Model, crate: str, header: str, source: str) -> CrateView:
    return Builder(model).build(crate, header, source)
