"""What the C++ and Rust back ends share when they walk types and members: the same IR
shapes are spelled the same way (primitive, string, sequence, array, named type) and the
same inputs are refused with the same words; each target gives only its spellings.

    class TypeMap(TypeSpeller):
        TARGET = "cpp"
        PRIMITIVES = {...}
        def string_type(self) -> str: ...
        def sequence_of(self, element: str) -> str: ...
        def array_of(self, element: str, n: int) -> str: ...
        def named(self, t: ir.TypeRef, decl: ir.Declaration, loc) -> str: ...
"""
from __future__ import annotations

from collections.abc import Iterator

from rapidgen.diagnostics import SourceLoc
from rapidgen.model import ir

NAMED_KINDS = ("struct", "union", "enum", "typedef")


class Unsupported(Exception):
    """The target cannot express this type; loc says where (None: the caller's place)."""

    def __init__(self, msg: str, loc: SourceLoc | None = None) -> None:
        super().__init__(msg)
        self.loc = loc


class TypeSpeller:
    TARGET = ""
    PRIMITIVES: dict[str, str] = {}

    def __init__(self, model: ir.Model) -> None:
        self.model = model

    def decl(self, t: ir.Type) -> ir.Declaration | None:
        return self.model.get(t.name) if isinstance(t, ir.TypeRef) else None

    def real(self, t: ir.Type) -> ir.Type:
        return self.model.resolve_alias(t)

    def spell(self, t: ir.Type, loc: SourceLoc) -> str:
        """The target's spelling of t, or Unsupported."""
        if isinstance(t, ir.Primitive):
            if t.name not in self.PRIMITIVES:
                raise Unsupported(f"'{t}' is not supported by the {self.TARGET} target", loc)
            return self.PRIMITIVES[t.name]
        if isinstance(t, ir.String):
            if t.wide:
                raise Unsupported(f"'wstring' is not supported by the {self.TARGET} target", loc)
            return self.string_type()
        if isinstance(t, ir.Sequence):
            return self.sequence_of(self.spell(t.element, loc))
        if isinstance(t, ir.Array):
            out = self.spell(t.element, loc)
            for n in reversed(t.dims):
                out = self.array_of(out, n)
            return out
        if isinstance(t, ir.TypeRef):
            d = self.decl(t)
            if d is None or d.kind not in NAMED_KINDS:
                raise Unsupported(f"{t.kind} '{t.name}' is not supported by the {self.TARGET} target", loc)
            return self.named(t, d, loc)
        raise Unsupported(f"'{t}' is not supported by the {self.TARGET} target (map, fixed)", loc)

    def string_type(self) -> str:
        raise NotImplementedError

    def sequence_of(self, element: str) -> str:
        raise NotImplementedError

    def array_of(self, element: str, n: int) -> str:
        raise NotImplementedError

    def named(self, t: ir.TypeRef, decl: ir.Declaration, loc: SourceLoc) -> str:
        raise NotImplementedError


def spelled_members(speller: TypeSpeller, model: ir.Model, s: ir.Struct,
                    problems: list[tuple[str, SourceLoc | None]]) -> Iterator[tuple[ir.Member, str]]:
    """Each member of s, base first, with its spelling; what the target cannot express
    (@optional members, unsupported types) goes to problems and is skipped."""
    for m in model.all_members(s):
        if m.optional:
            problems.append((f"@optional member '{m.name}' is not supported by the {speller.TARGET} target", m.loc))
            continue
        try:
            yield m, speller.spell(m.type, m.loc)
        except Unsupported as exc:
            problems.append((str(exc), exc.loc or m.loc))
