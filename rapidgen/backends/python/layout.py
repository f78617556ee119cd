"""Where each declaration lives in the generated package.

Declarations are grouped by the IDL file that declares them into one implementation
module each, `<package>/_idl/<File>.py`; the IDL modules become subpackages
(`<package>/rapid/`, `<package>/rapid/ext/`) that re-export their declarations.

Implementation modules import only each other (never a subpackage), so the import graph
is the file dependency graph. When files depend on each other in a cycle (possible with
forward declarations or files reopening a module around an #include), the files of the
cycle share one implementation module; every other import stays acyclic and no module
is ever imported half-initialised.
"""
from __future__ import annotations

import posixpath
from dataclasses import dataclass, field

from rapidgen.backends.python.typemap import default_refs
from rapidgen.model import ir
from rapidgen.model.order import strongly_connected


def type_refs(t: ir.Type) -> list[str]:
    """Scoped names a type expression refers to."""
    if isinstance(t, ir.TypeRef):
        return [t.name]
    if isinstance(t, (ir.Array, ir.Sequence)):
        return type_refs(t.element)
    if isinstance(t, ir.Map):
        return type_refs(t.key) + type_refs(t.value)
    return []


def references(model: ir.Model, d: ir.Declaration) -> list[str]:
    """Every declaration the Python code of `d` names (base members are flattened in;
    a member's default value may name more: the class behind a typedef, an enum, the
    branch a union selects by default)."""
    out: list[str] = []
    if isinstance(d, ir.Struct):
        for m in model.all_members(d):
            out += type_refs(m.type)
            if isinstance(m.default, ir.EnumValue):
                out.append(m.default.enum)
            elif m.default is None and not m.optional:
                out += default_refs(model, m.type)
    elif isinstance(d, ir.Union):
        out += type_refs(d.discriminator) + type_refs(model.resolve_alias(d.discriminator))
        for c in d.cases:
            out += type_refs(c.member.type)
            out += [label.enum for label in c.labels if isinstance(label, ir.EnumValue)]
    elif isinstance(d, ir.Typedef):
        out += type_refs(d.type)
    elif isinstance(d, ir.Const) and isinstance(d.value, ir.EnumValue):
        out.append(d.value.enum)
    return [n for n in dict.fromkeys(out) if n != d.scoped_name and model.get(n) is not None]


def module_path(scoped_name: str) -> tuple[str, ...]:
    """IDL module of a declaration: 'rapid::ext::X' -> ('rapid', 'ext')."""
    return tuple(scoped_name.split("::")[:-1])


@dataclass
class Chunk:
    """One implementation module: the declarations of one IDL file (or of a cycle of files)."""

    files: list[str]  # IDL files, first one names the module
    decls: list[str] = field(default_factory=list)  # scoped names, in model order

    @property
    def stem(self) -> str:
        base = posixpath.basename(self.files[0].replace("\\", "/"))
        return base[:-4] if base.lower().endswith(".idl") else base


@dataclass
class Layout:
    chunks: list[Chunk]
    chunk_of: dict[str, int]  # scoped name -> index in chunks
    modules: list[tuple[str, ...]]  # every IDL module path with its parents, sorted


def plan(model: ir.Model) -> Layout:
    file_of = {d.scoped_name: d.loc.file for d in model.declarations}
    files = list(dict.fromkeys(file_of.values()))  # first appearance in dependency order
    graph: dict[str, list[str]] = {f: [] for f in files}
    for d in model.declarations:
        for ref in references(model, d):
            target = file_of.get(ref)
            if target is not None and target != file_of[d.scoped_name] and target not in graph[file_of[d.scoped_name]]:
                graph[file_of[d.scoped_name]].append(target)
    groups = strongly_connected(files, graph)
    group_of = {f: i for i, g in enumerate(groups) for f in g}
    # chunks listed in order of first appearance of their files
    order = list(dict.fromkeys(group_of[f] for f in files))
    chunks = [Chunk(sorted(groups[g], key=files.index)) for g in order]
    index = {g: i for i, g in enumerate(order)}
    chunk_of: dict[str, int] = {}
    for d in model.declarations:
        i = index[group_of[file_of[d.scoped_name]]]
        chunks[i].decls.append(d.scoped_name)
        chunk_of[d.scoped_name] = i
    paths: set[tuple[str, ...]] = set()
    for m in model.modules:
        parts = tuple(m.scoped_name.split("::"))
        paths.update(parts[:i] for i in range(1, len(parts) + 1))
    for d in model.declarations:
        parts = module_path(d.scoped_name)
        paths.update(parts[:i] for i in range(1, len(parts) + 1))
    return Layout(chunks, chunk_of, sorted(paths))
