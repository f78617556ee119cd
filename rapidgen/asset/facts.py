"""What the descriptor checks need to know about the RAPID IDL, asked of the Model.

String bounds, sequence bounds, DataType enumerators and what the ParameterUnion carries
come from the IDL itself, so a RAPID set with other bounds is checked by its own rules.
Without a model (the IDL could not be loaded) every query answers None and the
model-based checks are skipped; the static shapes below keep value checks working.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from rapidgen.model.ir import (INTEGER_RANGES, Array, Enum, Model, Primitive, Sequence, String,
                               Struct, Typedef, Union)

MESSAGE = "rapid::Message"
FLOAT32_MAX = 3.4028234663852886e38


@dataclass(frozen=True)
class Shape:
    """What a DataType's union member holds: bool, int, float, string or a float array."""

    kind: str  # bool | int | float | string | array
    lo: float | None = None  # int and float limits
    hi: float | None = None
    bound: int | None = None  # string bound (IDL string<N>)
    count: int = 1  # array elements
    member: str = ""  # ParameterUnion member name (b, d, f, i, ll, s, vec3d, mat33f)
    element: str = ""  # array element primitive (float64, float32)


# The protocol's ParameterUnion, used when no model is at hand.
STATIC_SHAPES = {
    "RAPID_BOOL": Shape("bool", member="b"),
    "RAPID_DOUBLE": Shape("float", -1.7976931348623157e308, 1.7976931348623157e308, member="d"),
    "RAPID_FLOAT": Shape("float", -FLOAT32_MAX, FLOAT32_MAX, member="f"),
    "RAPID_INT": Shape("int", *INTEGER_RANGES["int32"], member="i"),
    "RAPID_LONGLONG": Shape("int", *INTEGER_RANGES["int64"], member="ll"),
    "RAPID_STRING": Shape("string", bound=128, member="s"),
    "RAPID_VEC3d": Shape("array", count=3, member="vec3d", element="float64"),
    "RAPID_MAT33f": Shape("array", count=9, member="mat33f", element="float32"),
}

# IDL spellings someone may write instead of a DataType, and the DataType that carries them.
IDL_TO_DATATYPE = {
    "boolean": "RAPID_BOOL", "bool": "RAPID_BOOL", "double": "RAPID_DOUBLE", "float64": "RAPID_DOUBLE",
    "float": "RAPID_FLOAT", "float32": "RAPID_FLOAT", "long": "RAPID_INT", "int32": "RAPID_INT",
    "int": "RAPID_INT", "long long": "RAPID_LONGLONG", "int64": "RAPID_LONGLONG", "string": "RAPID_STRING",
    "Vec3d": "RAPID_VEC3d", "Mat33f": "RAPID_MAT33f",
    # narrower or unsigned types: the nearest DataType that holds every value
    "short": "RAPID_INT", "int16": "RAPID_INT", "unsigned short": "RAPID_INT", "uint16": "RAPID_INT",
    "octet": "RAPID_INT", "uint8": "RAPID_INT", "int8": "RAPID_INT", "char": "RAPID_STRING",
    "unsigned long": "RAPID_LONGLONG", "uint32": "RAPID_LONGLONG",
    "Vec3f": "RAPID_VEC3d", "Vec2d": "RAPID_VEC3d", "Vec2f": "RAPID_VEC3d",
    "long double": "RAPID_DOUBLE",
}


class Facts:
    def __init__(self, model: Model | None) -> None:
        self.model = model

    @property
    def _model(self) -> Model:
        """The model, where something was already found in it."""
        assert self.model is not None
        return self.model

    # -- members ------------------------------------------------------------------
    def _member_type(self, struct: str, member: str):
        decl = self.model.get(struct) if self.model else None
        if not isinstance(decl, Struct):
            return None
        for m in self._model.all_members(decl):
            if m.name == member:
                return self._model.resolve_alias(m.type)
        return None

    def _string_bound(self, t) -> int | None:
        t = self._model.resolve_alias(t) if t is not None else None
        return t.bound if isinstance(t, String) else None

    def str_bound(self, struct: str, member: str) -> int | None:
        """N of the member's string<N>, or of its elements' when the member is a sequence."""
        t = self._member_type(struct, member)
        if isinstance(t, Sequence):
            t = t.element
        return self._string_bound(t)

    def seq_bound(self, struct: str, member: str) -> int | None:
        t = self._member_type(struct, member)
        return t.bound if isinstance(t, Sequence) else None

    # -- DataType and the ParameterUnion --------------------------------------------
    @cached_property
    def data_types(self) -> tuple[str, ...] | None:
        decl = self.model.get("rapid::DataType") if self.model else None
        return tuple(e.name for e in decl.enumerators) if isinstance(decl, Enum) else None

    @cached_property
    def shapes(self) -> dict[str, Shape]:
        """DataType enumerator -> Shape of the ParameterUnion member carrying it."""
        union = self.model.get("rapid::ParameterUnion") if self.model else None
        if not isinstance(union, Union):
            return dict(STATIC_SHAPES)
        out = {}
        for case in union.cases:
            shape = self._shape(case.member.type, case.member.name)
            for label in case.labels:
                name = getattr(label, "name", None)
                if name and shape:
                    out[name] = shape
        return out

    def _shape(self, t, member: str) -> Shape | None:
        t = self._model.resolve_alias(t)
        if isinstance(t, Primitive):
            if t.name == "boolean":
                return Shape("bool", member=member)
            if t.name in INTEGER_RANGES:
                return Shape("int", *INTEGER_RANGES[t.name], member=member)
            if t.name == "float32":
                return Shape("float", -FLOAT32_MAX, FLOAT32_MAX, member=member)
            if t.name in ("float64", "float128"):
                return Shape("float", -1.7976931348623157e308, 1.7976931348623157e308, member=member)
        if isinstance(t, String):
            return Shape("string", bound=t.bound, member=member)
        if isinstance(t, Array):
            elem = self._model.resolve_alias(t.element)
            count = 1
            for d in t.dims:
                count *= d
            if isinstance(elem, Primitive) and elem.name in ("float32", "float64"):
                return Shape("array", count=count, member=member, element=elem.name)
        return None

    def enumerators(self, enum: str) -> tuple[str, ...] | None:
        decl = self.model.get(enum) if self.model else None
        return tuple(e.name for e in decl.enumerators) if isinstance(decl, Enum) else None

    def is_idl_type(self, name: str) -> bool:
        if name in IDL_TO_DATATYPE:
            return True
        return self.model is not None and any(d.name == name for d in self.model.declarations
                                              if isinstance(d, (Struct, Typedef, Union, Enum)))

    # -- messages and topics ----------------------------------------------------------
    def struct(self, name: str) -> Struct | None:
        decl = self.model.get(name) if self.model else None
        return decl if isinstance(decl, Struct) else None

    def is_message(self, name: str) -> bool:
        cur = self.struct(name)
        return cur is not None and any(b.scoped_name == MESSAGE for b in self._model.lineage(cur))

    def struct_names(self) -> list[str]:
        return [d.scoped_name for d in self.model.declarations if isinstance(d, Struct)] if self.model else []

    def string_const(self, name: str) -> str | None:
        decl = self.model.get(name) if self.model else None
        value = getattr(decl, "value", None) if decl is not None and decl.kind == "const" else None
        return value if isinstance(value, str) else None

    def sequence_members(self, struct: str) -> tuple[str, ...] | None:
        """Own members of struct that are sequences (JointSample's per-joint arrays)."""
        decl = self.struct(struct)
        if decl is None:
            return None
        return tuple(m.name for m in decl.members
                     if isinstance(self._model.resolve_alias(m.type), Sequence))


def utf8_len(text: str) -> int:
    return len(text.encode("utf-8", errors="replace"))


def fits(text: str, bound: int | None) -> bool:
    """A string<N> holds N-1 bytes in RAPID: the C implementations keep a NUL in char[N]."""
    return bound is None or utf8_len(text) <= bound - 1


