"""IR -> view objects for the Python templates: every name, type string and import decided.

The package for one model:

    pyproject.toml
    <package>/__init__.py            imports the top-level IDL module packages
    <package>/_support.py            helpers the generated modules use
    <package>/qos.py                 runtime: each topic's QoS from the generated qos/ folder
    <package>/_idl/<File>.py         the declarations of one IDL file (dataclasses, enums, ...)
    <package>/<module>/__init__.py   one package per IDL module, re-exporting its declarations

Structs are flattened: a derived struct or valuetype lists its base's members first and
carries its full key (see docs/python-backend.md for why). Templates only print.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from rapidgen.backends import base
from rapidgen.backends.escape import py_str
from rapidgen.backends.python import namer
from rapidgen.backends.python.layout import Layout, module_path, plan
from rapidgen.backends.python.typemap import TypeMapper, Unsupported
from rapidgen.diagnostics import SourceLoc
from rapidgen.model import ir

CYCLONEDDS_REQUIREMENT = "cyclonedds>=11.0.1,<12"
RUNTIME_REQUIREMENT = "rapid-runtime>=0.1,<0.2"  # qos.py is rapid_runtime.qos (every package)
VERSION = "1.0.0"
# Runtime modules of the package root (besides _idl and _support): an IDL module or a
# global-scope declaration with one of these names is renamed (`qos`, `QoS` -> `qos_`, `QoS_`).
RUNTIME_MODULES = ("qos",)


# -- view objects --------------------------------------------------------------------------
@dataclass
class ImportLine:
    module: str
    names: list[str] = field(default_factory=list)  # `from module import names`; "A as B" allowed
    alias: str = ""  # `import module as alias` when names is empty
    is_from: bool = True
    multiline: bool = False


@dataclass
class MemberView:
    name: str
    type: str
    default: str = ""
    annotations: list[str] = field(default_factory=list)  # lines in the class body after the member


@dataclass
class ClassView:
    kind: Literal["struct", "union", "enum", "bitmask"]  # the macro that prints it
    name: str
    bases: str  # everything inside `class Name(...)`
    doc: str
    decorators: list[str] = field(default_factory=list)
    members: list[MemberView] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # comment lines
    lead: str = ""  # blank lines before it


@dataclass
class AssignView:
    kind: Literal["typedef", "const"]  # the macro that prints it
    name: str
    value: str
    lead: str = ""


@dataclass
class ModuleView:
    path: str
    header: str
    doc: str
    import_groups: list[list[ImportLine]]
    decls: list[ClassView | AssignView] = field(default_factory=list)
    exports: list[str] = field(default_factory=list)  # __all__
    has_exports: bool = False


@dataclass
class ProjectView:
    header: str
    name: str
    version: str
    description: str
    requirements: list[str]
    include: list[str]  # setuptools package globs


@dataclass
class QosRuntimeView:
    """`<package>/qos.py`: rapid_runtime.qos with the package's default folder; only the header
    and package name vary."""

    path: str
    header: str
    package: str


@dataclass
class PackageView:
    package: str
    project: ProjectView
    modules: list[ModuleView]  # every .py file but _support.py and qos.py
    support_path: str
    header: str
    type_count: int
    qos: QosRuntimeView


class UnsupportedInput(base.UnsupportedInput):
    """The model uses what the python target cannot express."""

    CODE = "RG1701"
    TARGET = "python"


# -- building -------------------------------------------------------------------------------
class _ModuleContext:
    """Names as seen from one implementation module; records what it must import."""

    def __init__(self, builder: "PythonViewBuilder", index: int) -> None:
        self.b = builder
        self.index = index
        self.scope = builder.chunk_scopes[index]
        self.defined: set[str] = set()
        self.imports: dict[int, dict[str, str]] = {}  # chunk -> {name in that chunk: local alias}
        self.uses_support = False

    def ref(self, scoped_name: str) -> tuple[str, bool]:
        target = self.b.layout.chunk_of[scoped_name]
        name = self.b.chunk_names[scoped_name]
        if target == self.index:
            return name, scoped_name not in self.defined
        alias = self.scope.claim(name, scoped_name)
        self.imports.setdefault(target, {})[name] = alias
        return alias, False

    def enumerator(self, enum_scoped: str, idl_name: str) -> str:
        return self.b.enumerators[enum_scoped][idl_name]

    def support(self) -> str:
        self.uses_support = True
        return "_support"


class PythonViewBuilder:
    def __init__(self, model: ir.Model, package: str, source: str, header: str) -> None:
        self.model = model
        self.package = package
        self.source = source
        self.header = header
        self.layout: Layout = plan(model)
        self.problems: list[tuple[str, SourceLoc | None]] = []
        files = namer.Scope("package _idl", namer.KEYWORDS | {"__init__"}, fold_case=True)
        self.file_names = [files.claim(namer.identifier(c.stem), c.files[0]) for c in self.layout.chunks]
        self.chunk_scopes = [namer.Scope(f"module _idl.{n}", namer.MODULE_RESERVED | {"_support"})
                             for n in self.file_names]
        self.chunk_names: dict[str, str] = {}
        for chunk, scope in zip(self.layout.chunks, self.chunk_scopes):
            for scoped in chunk.decls:
                self.chunk_names[scoped] = scope.claim(scoped.rsplit("::", 1)[-1], scoped)
        self.enumerators: dict[str, dict[str, str]] = {}
        for d in model.declarations:
            if isinstance(d, ir.Enum):
                scope = namer.Scope(f"enum {d.scoped_name}", namer.enumerator_reserved())
                self.enumerators[d.scoped_name] = {e.name: scope.claim(e.name, e.name) for e in d.enumerators}

    # -- the whole package -------------------------------------------------------------
    def build(self) -> PackageView:
        modules = [self._implementation(i) for i in range(len(self.layout.chunks))]
        if self.problems:
            raise UnsupportedInput(self.problems)
        modules += self._packages()
        modules.append(ModuleView(f"{self.package}/_idl/__init__.py", self.header,
                                  "Implementation modules, one per IDL file; import from the IDL module "
                                  "packages instead.", []))
        modules.sort(key=lambda m: m.path)
        types = sum(1 for d in self.model.declarations if not isinstance(d, ir.Const))
        project = ProjectView(self.header, self.package.replace("_", "-"), VERSION,
                              f"RAPID DDS types from {self.source} (cyclonedds.idl dataclasses)",
                              [CYCLONEDDS_REQUIREMENT, RUNTIME_REQUIREMENT], [self.package, f"{self.package}.*"])
        return PackageView(self.package, project, modules, f"{self.package}/_support.py", self.header, types,
                           QosRuntimeView(f"{self.package}/qos.py", self.header, self.package))

    def _packages(self) -> list[ModuleView]:
        """One package per IDL module (and the root): re-exports and subpackage imports."""
        paths: list[tuple[str, ...]] = [(), *self.layout.modules]
        dir_names: dict[tuple[str, ...], str] = {(): self.package}
        scopes: dict[tuple[str, ...], namer.Scope] = {}
        for path in paths:
            scopes[path] = namer.Scope(f"package {'::'.join(path) or self.package}",
                                       namer.KEYWORDS | {"_idl", "_support"})
        folders = {path: namer.Scope(f"folders of {'::'.join(path) or self.package}", namer.KEYWORDS, fold_case=True)
                   for path in paths}
        for runtime in RUNTIME_MODULES:  # taken first, so IDL names step aside (case-folded for folders)
            scopes[()].take(runtime, f"runtime module {runtime}.py")
            folders[()].take(runtime, f"runtime module {runtime}.py")
        for path in paths[1:]:
            folder = folders[path[:-1]].claim(path[-1], "module " + "::".join(path))
            scopes[path[:-1]].take(folder, "module " + "::".join(path))
            dir_names[path] = folder
        exports: dict[tuple[str, ...], dict[int, list[tuple[str, str]]]] = {p: {} for p in paths}
        for d in self.model.declarations:
            path = module_path(d.scoped_name)
            name = self.chunk_names[d.scoped_name]
            public = scopes[path].claim(name, d.scoped_name)
            exports[path].setdefault(self.layout.chunk_of[d.scoped_name], []).append((name, public))
        out = []
        for path in paths:
            scopes[path].check()
            depth = len(path)
            subs = sorted(dir_names[p] for p in paths[1:] if p[:-1] == path)
            lines = []
            names: list[str] = list(subs)
            for chunk in sorted(exports[path], key=lambda c: self.file_names[c]):
                items = sorted(exports[path][chunk], key=lambda x: x[1])
                names += [pub for _, pub in items]
                lines.append(self._from("." * (depth + 1) + "_idl." + self.file_names[chunk],
                                        [n if n == pub else f"{n} as {pub}" for n, pub in items]))
            if subs:
                lines.append(self._from(".", subs))
            folder = "/".join(dir_names[path[:i]] for i in range(1, depth + 1))
            rel = f"{self.package}/{folder + '/' if folder else ''}__init__.py"
            doc = (f"IDL module {'::'.join(path)}." if path else
                   f"Cyclone DDS types (cyclonedds.idl) generated from {self.source}.\n\n"
                   "Each IDL module is a subpackage; DDS type names are the IDL scoped names "
                   "(`rapid::Command`).")
            out.append(ModuleView(rel, self.header, doc, [lines] if lines else [], [],
                                  sorted(names), bool(names)))
        return out

    @staticmethod
    def _from(module: str, names: list[str]) -> ImportLine:
        return ImportLine(module, names, multiline=len(names) > 3)

    # -- one implementation module -----------------------------------------------------
    def _implementation(self, index: int) -> ModuleView:
        chunk = self.layout.chunks[index]
        ctx = _ModuleContext(self, index)
        mapper = TypeMapper(self.model, ctx)
        used: set[str] = set()
        decls: list[ClassView | AssignView] = []
        for scoped in chunk.decls:
            d = self.model.get(scoped)
            assert d is not None  # a chunk lists the model's own declarations
            try:
                view = self._declaration(d, mapper, used)
            except Unsupported as exc:
                self.problems.append((str(exc), exc.loc or d.loc))
                view = None
            if view is not None:
                decls.append(view)
            ctx.defined.add(scoped)
        for i, view in enumerate(decls):
            spaced = i == 0 or isinstance(view, ClassView) or isinstance(decls[i - 1], ClassView)
            view.lead = "\n\n" if spaced else ""
        ctx.scope.check()
        stdlib = []
        if used & {"dataclass", "field"}:
            stdlib.append(ImportLine("dataclasses", sorted(used & {"dataclass", "field"})))
        if "Decimal" in used:
            stdlib.append(ImportLine("decimal", ["Decimal"]))
        if "Optional" in used:
            stdlib.append(ImportLine("typing", ["Optional"]))
        runtime = [ImportLine(f"cyclonedds.{mod}", alias=alias, is_from=False)
                   for mod, alias in (("idl", "idl"), ("idl.annotations", "annotate"), ("idl.types", "types"))
                   if alias in used]
        local = [ImportLine("..", ["_support"])] if ctx.uses_support else []
        for target in sorted(ctx.imports, key=lambda c: self.file_names[c]):
            pairs = sorted(ctx.imports[target].items(), key=lambda x: x[1])
            local.append(self._from("." + self.file_names[target],
                                    [n if n == a else f"{n} as {a}" for n, a in pairs]))
        files = ", ".join(f.replace("\\", "/").rsplit("/", 1)[-1] for f in chunk.files)
        modules = sorted({"::".join(module_path(s)) or "(global scope)" for s in chunk.decls})
        doc = f"Declarations of {files} (IDL module{'s' * (len(modules) > 1)} {', '.join(modules)})."
        return ModuleView(f"{self.package}/_idl/{self.file_names[index]}.py", self.header, doc,
                          [g for g in (stdlib, runtime, local) if g], decls)

    def _declaration(self, d: ir.Declaration, mapper: TypeMapper, used: set[str]) -> ClassView | AssignView | None:
        name = self.chunk_names[d.scoped_name]
        typename = py_str(d.scoped_name.replace("::", "."))
        if isinstance(d, ir.Typedef):
            used.add("types")
            return AssignView("typedef", name, f"types.typedef[{typename}, {mapper.annotation(d.type, used, d.loc)}]")
        if isinstance(d, ir.Const):
            return AssignView("const", name, mapper.literal(d.value, used))
        if isinstance(d, ir.Struct):
            return self._struct(d, name, typename, mapper, used)
        if isinstance(d, ir.Union):
            return self._union(d, name, typename, mapper, used)
        if isinstance(d, ir.Enum):
            return self._enum(d, name, typename, used)
        if isinstance(d, ir.Bitmask):
            return self._bitmask(d, name, typename, used)
        raise Unsupported(f"{d.kind} '{d.scoped_name}' is not supported by the python target "
                          "(cyclonedds cannot encode it)", d.loc)

    def _struct(self, s: ir.Struct, name: str, typename: str, mapper: TypeMapper, used: set[str]) -> ClassView:
        members = self.model.all_members(s)
        body: set[str] = set()
        typed = []
        for m in members:
            ann = self._annotation(mapper, m.type, body, m.loc)
            if m.optional:
                body.add("Optional")
                ann = f"Optional[{ann}]"
            typed.append((m, ann, mapper.field_default(m.type, body, optional=m.optional, default=m.default)))
        scope = namer.Scope(f"struct {s.scoped_name}", namer.member_reserved("struct", body))
        top_keys = list(dict.fromkeys(k.split(".")[0] for k in s.keys))
        views = []
        sequential = 0  # the id cyclonedds gives a member with none written
        for m, ann, default in typed:
            py = scope.claim(m.name, m.name)
            lines = [f'annotate.member_name({py_str(py)}, {py_str(m.name)})'] if py != m.name else []
            if m.name in top_keys:
                lines.append(f"annotate.key({py_str(py)})")
            # The model's ids are written out wherever cyclonedds would not find the same:
            # it hashes Python names under autoid("hash"), and in a flattened class it
            # knows nothing of a base's @autoid. An @id is always written, as declared.
            if s.autoid == "HASH" or m.id is not None or m.member_id != sequential:
                lines.append(f"annotate.member_id({py_str(py)}, {m.member_id})")
            sequential = m.member_id + 1
            if m.external:
                lines.append(f"annotate.external({py_str(py)})")
            views.append(MemberView(py, ann, default, lines))
        scope.check()
        used |= body | {"dataclass", "annotate", "idl"}
        doc = f"IDL {s.origin} {s.scoped_name}"
        if s.base:
            doc += f" : {s.base}, flattened (base members first)"
        doc += "." + (f" Key: {', '.join(s.keys)}." if s.keys else "")
        return ClassView("struct", name, f"idl.IdlStruct, typename={typename}", doc,
                         [self._checked(mapper), "@dataclass"] + self._class_decorators(s), views,
                         self._key_notes(s, top_keys))

    def _annotation(self, mapper: TypeMapper, t: ir.Type, used: set[str], loc: SourceLoc) -> str:
        """A member's annotation; what cannot be mapped is recorded (every member is
        reported, not only the first) and generation fails at the end."""
        try:
            return mapper.annotation(t, used, loc)
        except Unsupported as exc:
            self.problems.append((str(exc), exc.loc or loc))
            return "None"

    @staticmethod
    def _checked(mapper: TypeMapper) -> str:
        """deserialize() raises one documented error for bad bytes (_support.DeserializeError)."""
        return f"@{mapper.ctx.support()}.checked"

    def _class_decorators(self, d: ir.Struct | ir.Union) -> list[str]:
        out = [f"@annotate.{d.extensibility}"]
        if d.nested:
            out.append("@annotate.nested")
        if d.autoid == "HASH":
            out.append('@annotate.autoid("hash")')
        return out

    def _key_notes(self, s: ir.Struct, top_keys: list[str]) -> list[str]:
        """cyclonedds keys on whole members: say so when the IDL key paths differ from that."""
        members = {m.name: m for m in self.model.all_members(s)}
        implied: list[str] = []
        for k in top_keys:
            implied += self._expand(k, members[k].type, 0) if k in members else [k]
        if implied == list(s.keys):
            return []
        return [f"IDL key {', '.join(s.keys)}; cyclonedds keys on whole members, so the instance key",
                f"here is {', '.join(implied)}."]

    def _expand(self, prefix: str, t: ir.Type, depth: int) -> list[str]:
        real = self.model.resolve_alias(t)
        d = self.model.get(real.name) if isinstance(real, ir.TypeRef) else None
        if isinstance(d, ir.Struct) and depth < 32:
            if d.keys:
                return [f"{prefix}.{k}" for k in d.keys]
            out = []
            for m in self.model.all_members(d):
                out += self._expand(f"{prefix}.{m.name}", m.type, depth + 1)
            return out
        return [prefix]

    def _union(self, u: ir.Union, name: str, typename: str, mapper: TypeMapper, used: set[str]) -> ClassView:
        body: set[str] = {"types"}
        disc = mapper.discriminator(u.discriminator, body, u.loc)
        cases = []
        for c in u.cases:
            inner = self._annotation(mapper, c.member.type, body, c.member.loc)
            if c.is_default:
                cases.append((c, f"types.default[{inner}]"))
            else:
                labels = ", ".join(mapper.literal(lab, body) for lab in c.labels)
                cases.append((c, f"types.case[[{labels}], {inner}]"))
        scope = namer.Scope(f"union {u.scoped_name}", namer.member_reserved("union", body))
        views = []
        for c, ann in cases:
            py = scope.claim(c.member.name, c.member.name)
            lines = [f'annotate.member_name({py_str(py)}, {py_str(c.member.name)})'] if py != c.member.name else []
            views.append(MemberView(py, ann, "", lines))
        scope.check()
        used |= body | {"annotate", "idl"}
        bases = f"idl.IdlUnion, discriminator={disc}"
        if u.discriminator_key:
            bases += ", discriminator_is_key=True"
        doc = f"IDL union {u.scoped_name} switch ({u.discriminator})."
        return ClassView("union", name, f"{bases}, typename={typename}", doc,
                         [self._checked(mapper)] + self._class_decorators(u), views)

    def _enum(self, e: ir.Enum, name: str, typename: str, used: set[str]) -> ClassView:
        names = self.enumerators[e.scoped_name]
        bases = f"idl.IdlEnum, typename={typename}"
        if e.default_declared:
            bases += f", default={py_str(names[e.default])}"
        decorators = [f"@annotate.bit_bound({e.bit_bound})"] if e.bit_bound != 32 else []
        if e.extensibility != "final":
            decorators.append(f"@annotate.{e.extensibility}")
        used |= {"idl"} | ({"annotate"} if decorators else set())
        members = [MemberView(names[en.name], "", str(en.value)) for en in e.enumerators]
        return ClassView("enum", name, bases, f"IDL enum {e.scoped_name}.", decorators, members)

    def _bitmask(self, b: ir.Bitmask, name: str, typename: str, used: set[str]) -> ClassView:
        scope = namer.Scope(f"bitmask {b.scoped_name}", namer.MODULE_RESERVED)
        members = []
        for v in b.values:
            py = scope.claim(v.name, v.name)
            members.append(MemberView(py, "bool", "False", [f"annotate.position({py_str(py)}, {v.position})"]))
        used |= {"dataclass", "annotate", "idl"}
        return ClassView("bitmask", name, f"idl.IdlBitmask, typename={typename}", f"IDL bitmask {b.scoped_name}.",
                         ["@dataclass", f"@annotate.bit_bound({b.bit_bound})"], members)


def build(model: ir.Model, package: str, source: str, header: str) -> PackageView:
    return PythonViewBuilder(model, package, source, header).build()
