"""The unresolved syntax tree produced by parse.py and consumed by model/resolve.py.

Names here are as written (relative or absolute), expressions are unevaluated and
types are unresolved; resolution turns this into the Model (rapidgen.model.ir).
"""
from __future__ import annotations

from dataclasses import dataclass

from rapidgen.diagnostics import SourceLoc


@dataclass(frozen=True, slots=True)
class ScopedName:
    parts: tuple[str, ...]
    absolute: bool
    loc: SourceLoc

    def __str__(self) -> str:
        return ("::" if self.absolute else "") + "::".join(self.parts)


# -- constant expressions ----------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Literal:
    kind: str  # int | float | fixed | char | wchar | string | wstring | bool
    value: object
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class NameRef:
    name: ScopedName
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class Unary:
    op: str
    operand: "Expr"
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class Binary:
    op: str
    left: "Expr"
    right: "Expr"
    loc: SourceLoc


Expr = Literal | NameRef | Unary | Binary


# -- annotations -------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class AnnotationAppl:
    name: str  # as written, e.g. "key" or "::my::ann"
    params: tuple[tuple[str | None, Expr], ...]
    loc: SourceLoc


# -- type specs ----------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class BaseType:
    name: str  # IR primitive name: int32, float64, char8, boolean, octet, ...
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class NamedType:
    name: ScopedName
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class SequenceType:
    element: "TypeSpec"
    bound: Expr | None
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class StringType:
    bound: Expr | None
    wide: bool
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class MapType:
    key: "TypeSpec"
    value: "TypeSpec"
    bound: Expr | None
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class FixedType:
    digits: Expr | None  # None for the bare `fixed` const type
    scale: Expr | None
    loc: SourceLoc


TypeSpec = BaseType | NamedType | SequenceType | StringType | MapType | FixedType


# -- declarations --------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Declarator:
    name: str
    dims: tuple[Expr, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class MemberDecl:
    annotations: tuple[AnnotationAppl, ...]
    type: TypeSpec
    declarators: tuple[Declarator, ...]
    loc: SourceLoc
    key_comment: bool = False  # trailing `//@key` (RTI dialect)
    visibility: str | None = None  # valuetype state members: public | private


@dataclass(frozen=True, slots=True)
class StructDecl:
    name: str
    base: ScopedName | None
    members: tuple[MemberDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc
    origin: str = "struct"  # struct | valuetype
    exports: tuple["Definition", ...] = ()  # consts/typedefs declared inside a valuetype


@dataclass(frozen=True, slots=True)
class ForwardDecl:
    kind: str  # struct | union | valuetype
    name: str
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class CaseDecl:
    labels: tuple[Expr | None, ...]  # None is `default`
    member: MemberDecl
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class UnionDecl:
    name: str
    discriminator: TypeSpec
    disc_annotations: tuple[AnnotationAppl, ...]
    cases: tuple[CaseDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class EnumeratorDecl:
    name: str
    value: Expr | None
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class EnumDecl:
    name: str
    enumerators: tuple[EnumeratorDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class BitValueDecl:
    name: str
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class BitmaskDecl:
    name: str
    values: tuple[BitValueDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class BitfieldDecl:
    width: Expr
    type: TypeSpec | None
    names: tuple[str, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class BitsetDecl:
    name: str
    base: ScopedName | None
    fields: tuple[BitfieldDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class TypedefDecl:
    type: TypeSpec
    declarators: tuple[Declarator, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class ConstDecl:
    type: TypeSpec
    name: str
    value: Expr
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class NativeDecl:
    name: str
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class ModuleDecl:
    name: str
    definitions: tuple["Definition", ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class KeylistPragma:
    type: ScopedName
    members: tuple[tuple[str, SourceLoc], ...]  # dotted paths
    loc: SourceLoc


@dataclass(frozen=True, slots=True)
class AnnotationDecl:
    name: str
    loc: SourceLoc


Definition = (ModuleDecl | StructDecl | ForwardDecl | UnionDecl | EnumDecl | BitmaskDecl
              | BitsetDecl | TypedefDecl | ConstDecl | NativeDecl | KeylistPragma | AnnotationDecl)


@dataclass(frozen=True, slots=True)
class Specification:
    definitions: tuple[Definition, ...]
    files: tuple[str, ...]
