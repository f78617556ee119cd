"""IR types -> Rust type spellings, default expressions, minimum sizes, and the XCDR1
expressions encoding, decoding and sizing a value (straight-line calls on
cdr::Writer/Reader/Size; sequences and arrays of primitives and booleans at once, closures
or loops only for the elements of other sequences and arrays).

Value places: `self.x` (a struct field) or `*e` (a closure's or match's reference).
"""
from __future__ import annotations

import math
import struct as _struct
from typing import Callable

import re

from rapidgen.backends import escape
from rapidgen.backends.typewalk import TypeSpeller
from rapidgen.diagnostics import SourceLoc
from rapidgen.model import ir, wire
from rapidgen.model.wire import enum_size

PRIMITIVES = {
    "int8": "i8", "uint8": "u8", "int16": "i16", "uint16": "u16", "int32": "i32", "uint32": "u32",
    "int64": "i64", "uint64": "u64", "float32": "f32", "float64": "f64", "char8": "u8", "boolean": "bool",
    "octet": "u8",
}
ENUM_REPR = {1: "i8", 2: "i16", 4: "i32"}
# Arrays up to this length have Default (the standard library's limit); longer ones are
# built with std::array::from_fn.
STD_ARRAY_DEFAULT = 32
# serde's derive handles arrays up to this length; a member holding a longer one (at any
# depth, also inside sequences) goes through the generated module serde_arrays.
SERDE_ARRAY_MAX = 32
SERDE_ARRAYS = "crate::serde_arrays"
CDR = "crate::cdr"


_PLAIN = re.compile(r'[ !#-\[\]-~]*')  # printable ASCII but '"' and '\\': what rust_str keeps as it is


def rust_str(text: str) -> str:
    """escape.rust_str (the one definition), without its character loop for text it keeps as
    it is: the view quotes a member path or two per member."""
    return f'"{text}"' if _PLAIN.fullmatch(text) else escape.rust_str(text)


def ref(place: str) -> str:
    """A reference to the value at `place`."""
    return place[1:] if place.startswith("*") else "&" + place


def mut_ref(place: str) -> str:
    """A mutable reference to the value at `place`."""
    return place[1:] if place.startswith("*") else "&mut " + place


class TypeMap(TypeSpeller):
    """Needs the model and a function giving a declaration's path from the crate root."""

    TARGET = "rust"
    PRIMITIVES = PRIMITIVES

    def __init__(self, model: ir.Model, path: Callable[[str], str]) -> None:
        super().__init__(model)
        self.real = model.resolve_alias  # type: ignore[method-assign]  # TypeSpeller.real, one call less
        self.path = path
        self.variant: Callable[[ir.Enum, str], str] = lambda e, n: n  # set by the view
        self._n = 0

    def var(self, stem: str) -> str:
        """A fresh local variable name (`e1`, `a2`, ...)."""
        self._n += 1
        return f"{stem}{self._n}"

    # -- spelling (typewalk.TypeSpeller.spell walks; these spell) ---------------------
    def rust(self, t: ir.Type, loc: SourceLoc) -> str:
        return self.spell(t, loc)

    def string_type(self) -> str:
        return "::std::string::String"

    def sequence_of(self, element: str) -> str:
        return f"::std::vec::Vec<{element}>"

    def array_of(self, element: str, n: int) -> str:
        return f"[{element}; {n}]"

    def named(self, t: ir.TypeRef, decl: ir.Declaration, loc: SourceLoc) -> str:
        if isinstance(decl, ir.Typedef):
            self.spell(decl.type, loc)  # refuse what the alias names, at this use too
        return self.path(t.name)

    def default(self, t: ir.Type) -> str | None:
        """A default expression, or None where `Default::default()` gives the IDL default
        (zeros, empty, the enum's default enumerator, the union's default branch)."""
        r = self.real(t)
        if isinstance(r, ir.Array):
            inner = self.default(ir.Array(r.element, r.dims[1:]) if len(r.dims) > 1 else r.element)
            if inner is None and r.dims[0] <= STD_ARRAY_DEFAULT:
                return None
            return f"::std::array::from_fn(|_| {inner or '::core::default::Default::default()'})"
        return None

    def literal(self, value: ir.ConstValue, t: ir.Type) -> str:
        """A Rust constant expression of type t holding value."""
        r = self.real(t)
        if isinstance(value, ir.EnumValue):
            e = self.model.get(value.enum)
            return f"{self.path(value.enum)}::{self.variant(e, value.name)}"  # type: ignore[arg-type]
        if isinstance(value, bool):
            return "true" if value else "false"
        name = r.name if isinstance(r, ir.Primitive) else ""
        if isinstance(value, str):
            return str(ord(value)) if name == "char8" and len(value) == 1 else rust_str(value)
        if name in ("float32", "float64") or not isinstance(value, int):
            return float_literal(float(value), PRIMITIVES.get(name, "f64"))
        return str(value)

    # -- sizes ------------------------------------------------------------------------
    def min_size(self, t: ir.Type) -> int:
        """Fewest bytes a value takes on the wire (model/wire.py)."""
        return wire.min_size(self.model, t)

    # -- serde --------------------------------------------------------------------------
    def serde_with(self, t: ir.Type) -> str | None:
        """The `#[serde(with = ...)]` path for a value of type t holding an array longer than
        serde's derive takes (`Arr::<Plain>` for `[f64; 40]`, `Seq::<Arr::<Plain>>` for a
        sequence of them); None when serde's own impls do."""
        r = self.real(t)
        if isinstance(r, ir.Sequence):
            inner = self.serde_with(r.element)
            return None if inner is None else f"{SERDE_ARRAYS}::Seq::<{inner}>"
        if isinstance(r, ir.Array):
            inner = self.serde_with(ir.Array(r.element, r.dims[1:]) if len(r.dims) > 1 else r.element)
            if inner is None and r.dims[0] <= SERDE_ARRAY_MAX:
                return None
            return f"{SERDE_ARRAYS}::Arr::<{inner or SERDE_ARRAYS + '::Plain'}>"
        return None

    # -- encode -----------------------------------------------------------------------
    def encode(self, t: ir.Type, place: str, what: str) -> tuple[str, bool]:
        """An expression writing the value at `place` to Writer `w`, and whether it is a
        Result (to be followed by `?`)."""
        r = self.real(t)
        if isinstance(r, ir.Primitive):
            if r.name == "boolean":
                return f"w.put_bool({place})", False
            return f"w.put::<{PRIMITIVES[r.name]}>({place})", False
        w = rust_str(what) if isinstance(r, (ir.String, ir.Sequence)) else ""
        if isinstance(r, ir.String):
            return f"w.put_string({ref(place)}, {r.bound or 0}, {w})", True
        if isinstance(r, ir.Sequence):
            run = self.run(r.element)
            if run:
                return f"w.put_seq_{run}({ref(place)}, {r.bound or 0}, {w})", True
            e = self.var("e")
            return f"w.put_seq({ref(place)}, {r.bound or 0}, {w}, |w, {e}| {self._closure(r.element, e, what)})", True
        if isinstance(r, ir.Array):
            inner = ir.Array(r.element, r.dims[1:]) if len(r.dims) > 1 else r.element
            run = self.run(inner)
            if run:
                return f"w.put_{run}({ref(place)})", False
            e = self.var("e")
            return f"w.put_array({ref(place)}, |w, {e}| {self._closure(inner, e, what)})", True
        return f"{CDR}::Cdr::encode({ref(place)}, w)", True

    def run(self, t: ir.Type) -> str:
        """`prims::<T>` / `bools` when elements of type t go at once (primitives, booleans);
        "" otherwise (enums too: each value is checked on decode)."""
        r = self.real(t)
        if not isinstance(r, ir.Primitive):
            return ""
        return "bools" if r.name == "boolean" else f"prims::<{PRIMITIVES[r.name]}>"

    def _closure(self, t: ir.Type, e: str, what: str) -> str:
        expr, fallible = self.encode(t, "*" + e, what)
        return expr if fallible else f"{{ {expr}; Ok(()) }}"

    # -- size -------------------------------------------------------------------------
    def size(self, t: ir.Type, place: str) -> str:
        """A statement adding the bytes `encode` writes for the value at `place` to Size `s`
        (a primitive's or an enum's does not read the place)."""
        r = self.real(t)
        if isinstance(r, ir.Primitive):
            return "s.bytes(1);" if r.name == "boolean" else f"s.put::<{PRIMITIVES[r.name]}>();"
        if isinstance(r, ir.String):
            return f"s.string({ref(place)});"
        if isinstance(r, (ir.Sequence, ir.Array)):
            inner = r.element if isinstance(r, ir.Sequence) or len(r.dims) == 1 else ir.Array(r.element, r.dims[1:])
            count = "s.count(); " if isinstance(r, ir.Sequence) else ""
            run = self.run(inner)
            if run:
                n = f"{place.lstrip('*')}.len()"
                return f"{count}s.{'bytes' if run == 'bools' else run}({n});"
            e = self.var("e")
            return f"{count}for {e} in {ref(place)} {{ {self.size(inner, '*' + e)} }}"
        d = self.decl(r)
        if isinstance(d, ir.Enum):  # the same size for every value (the place may be "")
            return f"s.put::<{ENUM_REPR[enum_size(d)]}>();"
        return f"{CDR}::Cdr::size({ref(place)}, s);"

    # -- decode -----------------------------------------------------------------------
    def decode(self, t: ir.Type, what: str) -> str:
        """An expression of the value read from Reader `r` (`?` inside)."""
        expr, is_result = self._decode(t, what)
        return expr + "?" if is_result else expr

    def decoder(self, t: ir.Type, what: str) -> str:
        """A function (or closure) `FnMut(&mut Reader) -> Result<T, DecodeError>`."""
        r = self.real(t)
        d = self.decl(r)
        if isinstance(d, (ir.Struct, ir.Union, ir.Enum)):
            return f"<{self.path(d.scoped_name)} as {CDR}::Cdr>::decode"
        expr, is_result = self._decode(t, what)
        return f"|r| {expr}" if is_result else f"|r| Ok({expr})"

    def _decode(self, t: ir.Type, what: str) -> tuple[str, bool]:
        r = self.real(t)
        if isinstance(r, ir.Primitive):
            if r.name == "boolean":
                return "r.get_bool()", True
            return f"r.get::<{PRIMITIVES[r.name]}>()", True
        w = rust_str(what) if isinstance(r, (ir.String, ir.Sequence, ir.Array)) else ""
        if isinstance(r, ir.String):
            return f"r.get_string({r.bound or 0}, {w})", True
        if isinstance(r, ir.Sequence):
            run = self.run(r.element)
            if run:
                return f"r.get_seq_{run}({r.bound or 0}, {w})", True
            return (f"r.get_seq({r.bound or 0}, {self.min_size(r.element)}, {w}, "
                    f"{self.decoder(r.element, what)})"), True
        if isinstance(r, ir.Array):
            inner = ir.Array(r.element, r.dims[1:]) if len(r.dims) > 1 else r.element
            a = self.var("a")
            init = self.default(r) or "::core::default::Default::default()"
            run = self.run(inner)
            fill = (f"r.get_{run}(&mut {a}, {w})?;" if run
                    else f"r.get_array(&mut {a}, {self.decoder(inner, what)})?;")
            return (f"{{ r.need({self.min_size(r)}, {w})?; let mut {a}: {self.rust(t, SourceLoc('', 0, 0))} = {init}; "
                    f"{fill} {a} }}"), False
        d = self.decl(r)
        assert d is not None
        return f"<{self.path(d.scoped_name)} as {CDR}::Cdr>::decode(r)", True


    # -- decode into (a kept value: its strings' and sequences' capacity reused) --------
    def decode_into(self, t: ir.Type, place: str, what: str) -> str:
        """A statement reading the value from Reader `r` over the one at `place` (`?`
        inside): the same reads and checks as `decode`, in the same order."""
        r = self.real(t)
        if isinstance(r, ir.Primitive):
            return f"{place} = {self.decode(t, what)};"
        w = rust_str(what) if isinstance(r, (ir.String, ir.Sequence, ir.Array)) else ""
        at = mut_ref(place)
        if isinstance(r, ir.String):
            return f"r.get_string_into({at}, {r.bound or 0}, {w})?;"
        if isinstance(r, ir.Sequence):
            run = self.run(r.element)
            if run:
                name, _, turbofish = run.partition("::")
                return f"r.get_seq_{name}_into{'::' + turbofish if turbofish else ''}({at}, {r.bound or 0}, {w})?;"
            e = self.var("e")
            return (f"r.get_seq_into({at}, {r.bound or 0}, {self.min_size(r.element)}, {w}, "
                    f"|r, {e}| {{ {self.decode_into(r.element, '*' + e, what)} Ok(()) }}, "
                    f"{self.decoder(r.element, what)})?;")
        if isinstance(r, ir.Array):
            inner = ir.Array(r.element, r.dims[1:]) if len(r.dims) > 1 else r.element
            run = self.run(inner)
            if run:
                fill = f"r.get_{run}({at}, {w})?;"
            else:
                e = self.var("e")
                fill = f"r.get_array_into({at}, |r, {e}| {{ {self.decode_into(inner, '*' + e, what)} Ok(()) }})?;"
            return f"r.need({self.min_size(r)}, {w})?; {fill}"
        d = self.decl(r)
        assert d is not None
        return f"{CDR}::Cdr::decode_into({at}, r)?;"


def float_literal(v: float, rtype: str) -> str:
    """A Rust literal of v: the shortest decimal that reads back as the same f32 or f64."""
    if math.isnan(v):
        return f"{rtype}::NAN"
    if math.isinf(v):
        return f"{rtype}::{'NEG_' if v < 0 else ''}INFINITY"
    if rtype == "f32":  # the shortest decimal that is the same float32 (no excessive precision)
        bits = _struct.pack("<f", v)
        for p in range(1, 10):
            text = f"{v:.{p}g}"
            if _struct.pack("<f", float(text)) == bits:
                break
    else:
        text = repr(v)
    if not any(c in text for c in ".en"):
        text += ".0"
    return text
