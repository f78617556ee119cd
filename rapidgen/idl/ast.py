"""The unresolved syntax tree produced by parse.py and consumed by model/resolve.py.

Names here are as written (relative or absolute), expressions are unevaluated and
types are unresolved; resolution turns this into the Model (rapidgen.model.ir).
Nodes are NamedTuples: immutable, and much cheaper to create than frozen dataclasses
(the parser makes tens of thousands); the model proper uses frozen dataclasses.
"""
from __future__ import annotations

from decimal import Decimal
from typing import NamedTuple

from rapidgen.diagnostics import SourceLoc


class ScopedName(NamedTuple):
    parts: tuple[str, ...]
    absolute: bool
    loc: SourceLoc

    def __str__(self) -> str:
        return ("::" if self.absolute else "") + "::".join(self.parts)


# -- constant expressions ----------------------------------------------------------
class Literal(NamedTuple):
    kind: str  # int | float | fixed | char | wchar | string | wstring | bool
    value: int | float | Decimal | str | bool
    loc: SourceLoc


class NameRef(NamedTuple):
    name: ScopedName
    loc: SourceLoc


class Unary(NamedTuple):
    op: str
    operand: "Expr"
    loc: SourceLoc


class Binary(NamedTuple):
    op: str
    left: "Expr"
    right: "Expr"
    loc: SourceLoc


Expr = Literal | NameRef | Unary | Binary


# -- annotations -------------------------------------------------------------------
class AnnotationAppl(NamedTuple):
    name: str  # as written, e.g. "key" or "::my::ann"
    params: tuple[tuple[str | None, Expr], ...]
    loc: SourceLoc


# -- type specs ----------------------------------------------------------------------
class BaseType(NamedTuple):
    name: str  # IR primitive name: int32, float64, char8, boolean, octet, ...
    loc: SourceLoc


class NamedType(NamedTuple):
    name: ScopedName
    loc: SourceLoc


class SequenceType(NamedTuple):
    element: "TypeSpec"
    bound: Expr | None
    loc: SourceLoc


class StringType(NamedTuple):
    bound: Expr | None
    wide: bool
    loc: SourceLoc


class MapType(NamedTuple):
    key: "TypeSpec"
    value: "TypeSpec"
    bound: Expr | None
    loc: SourceLoc


class FixedType(NamedTuple):
    digits: Expr | None  # None for the bare `fixed` const type
    scale: Expr | None
    loc: SourceLoc


TypeSpec = BaseType | NamedType | SequenceType | StringType | MapType | FixedType


# -- declarations --------------------------------------------------------------------
class Declarator(NamedTuple):
    name: str
    dims: tuple[Expr, ...]
    loc: SourceLoc


class MemberDecl(NamedTuple):
    annotations: tuple[AnnotationAppl, ...]
    type: TypeSpec
    declarators: tuple[Declarator, ...]
    loc: SourceLoc
    key_comment: bool = False  # trailing `//@key` (RTI dialect)
    visibility: str | None = None  # valuetype state members: public | private


class StructDecl(NamedTuple):
    name: str
    base: ScopedName | None
    members: tuple[MemberDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc
    origin: str = "struct"  # struct | valuetype
    exports: tuple["Definition", ...] = ()  # consts/typedefs declared inside a valuetype


class ForwardDecl(NamedTuple):
    kind: str  # struct | union | valuetype
    name: str
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class CaseDecl(NamedTuple):
    labels: tuple[Expr | None, ...]  # None is `default`
    member: MemberDecl
    loc: SourceLoc


class UnionDecl(NamedTuple):
    name: str
    discriminator: TypeSpec
    disc_annotations: tuple[AnnotationAppl, ...]
    cases: tuple[CaseDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class EnumeratorDecl(NamedTuple):
    name: str
    value: Expr | None
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class EnumDecl(NamedTuple):
    name: str
    enumerators: tuple[EnumeratorDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class BitValueDecl(NamedTuple):
    name: str
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class BitmaskDecl(NamedTuple):
    name: str
    values: tuple[BitValueDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class BitfieldDecl(NamedTuple):
    width: Expr
    type: TypeSpec | None
    names: tuple[str, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class BitsetDecl(NamedTuple):
    name: str
    base: ScopedName | None
    fields: tuple[BitfieldDecl, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class TypedefDecl(NamedTuple):
    type: TypeSpec
    declarators: tuple[Declarator, ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class ConstDecl(NamedTuple):
    type: TypeSpec
    name: str
    value: Expr
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class NativeDecl(NamedTuple):
    name: str
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class ModuleDecl(NamedTuple):
    name: str
    definitions: tuple["Definition", ...]
    annotations: tuple[AnnotationAppl, ...]
    loc: SourceLoc


class KeylistPragma(NamedTuple):
    type: ScopedName
    members: tuple[tuple[str, SourceLoc], ...]  # dotted paths
    loc: SourceLoc


class AnnotationDecl(NamedTuple):
    name: str
    loc: SourceLoc


Definition = (ModuleDecl | StructDecl | ForwardDecl | UnionDecl | EnumDecl | BitmaskDecl
              | BitsetDecl | TypedefDecl | ConstDecl | NativeDecl | KeylistPragma | AnnotationDecl)


class Specification(NamedTuple):
    definitions: tuple[Definition, ...]
    files: tuple[str, ...]
