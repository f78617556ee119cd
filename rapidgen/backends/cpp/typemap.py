"""IR types -> C++ type spellings, default values, sizes, and the XCDR1 statements that
encode and decode a value of each type (straight-line: one call per primitive, bulk copies
for sequences and arrays of numbers, loops only for composite elements)."""
from __future__ import annotations

import math
from decimal import Decimal
from typing import Callable

from rapidgen.backends.escape import cpp_str
from rapidgen.backends.typewalk import TypeSpeller
from rapidgen.diagnostics import SourceLoc
from rapidgen.model import ir, wire
from rapidgen.model.wire import PRIMITIVE_SIZES as SIZES
from rapidgen.model.wire import enum_size

PRIMITIVES = {
    "int8": "std::int8_t", "uint8": "std::uint8_t", "int16": "std::int16_t", "uint16": "std::uint16_t",
    "int32": "std::int32_t", "uint32": "std::uint32_t", "int64": "std::int64_t", "uint64": "std::uint64_t",
    "float32": "float", "float64": "double", "char8": "char", "boolean": "bool", "octet": "std::uint8_t",
}
ENUM_TYPES = {1: "std::int8_t", 2: "std::int16_t", 4: "std::int32_t"}
UNBOUNDED = 1 << 62  # a size no bounded type reaches: "no bound"


class TypeMap(TypeSpeller):
    """Needs the model and a function giving a declaration's qualified C++ name."""

    TARGET = "cpp"
    PRIMITIVES = PRIMITIVES

    def __init__(self, model: ir.Model, qualified: Callable[[str], str]) -> None:
        super().__init__(model)
        self.q = qualified
        self._loop = 0
        self._max: dict[str, int] = {}  # a struct's or union's max_size, once known exactly

    # -- spelling (typewalk.TypeSpeller.spell walks; these spell) ---------------------
    def cpp(self, t: ir.Type, loc: SourceLoc) -> str:
        return self.spell(t, loc)

    def string_type(self) -> str:
        return "std::string"

    def sequence_of(self, element: str) -> str:
        return f"std::vector<{element}>"

    def array_of(self, element: str, n: int) -> str:
        return f"std::array<{element}, {n}>"

    def named(self, t: ir.TypeRef, decl: ir.Declaration, loc: SourceLoc) -> str:
        return self.q(t.name)

    def default(self, t: ir.Type, loc: SourceLoc) -> str:
        """Brace initializer of a member: `{}` (zero, empty) or the enum's default enumerator."""
        r = self.real(t)
        d = self.decl(r)
        if isinstance(d, ir.Enum):
            return "{" + self.q(d.scoped_name) + "::" + self.enumerator(d, d.default) + "}"
        return "{}"

    def enumerator(self, e: ir.Enum, name: str) -> str:
        raise NotImplementedError  # set by the view (its enumerator scopes)

    def literal(self, value: ir.ConstValue, t: ir.Type, loc: SourceLoc) -> str:
        """A C++ constant expression of type t holding value."""
        r = self.real(t)
        if isinstance(value, ir.EnumValue):
            e = self.model.get(value.enum)
            return f"{self.q(value.enum)}::{self.enumerator(e, value.name)}"  # type: ignore[arg-type]
        if isinstance(value, bool):
            return "true" if value else "false"
        name = r.name if isinstance(r, ir.Primitive) else ""
        if isinstance(value, str):
            return f"static_cast<char>({ord(value)})" if name == "char8" and len(value) == 1 else cpp_str(value)
        name = r.name if isinstance(r, ir.Primitive) else "float64"
        if isinstance(value, (float, Decimal)) or name in ("float32", "float64"):
            v = float(value)
            lim = f"std::numeric_limits<{PRIMITIVES.get(name, 'double')}>"
            if math.isnan(v):
                return f"{lim}::quiet_NaN()"
            if math.isinf(v):
                return f"{'-' if v < 0 else ''}{lim}::infinity()"
            return f"static_cast<{PRIMITIVES.get(name, 'double')}>({v.hex()})" if name == "float32" else repr(v)
        ctype = PRIMITIVES.get(name, "std::int64_t")
        if name == "char8":
            return f"static_cast<char>({int(value)})"
        if value == -2**63:
            return f"static_cast<{ctype}>(-9223372036854775807LL - 1)"
        return f"static_cast<{ctype}>({value}{'ULL' if value > 2**63 - 1 else 'LL'})"

    # -- sizes ------------------------------------------------------------------------
    def min_size(self, t: ir.Type) -> int:
        """Fewest bytes a value takes on the wire (model/wire.py)."""
        return wire.min_size(self.model, t)

    def max_size(self, t: ir.Type, depth: int = 0) -> int:
        """Most bytes a value can take, padding counted at its worst; UNBOUNDED if none."""
        r = self.real(t)
        if depth > 50:
            return UNBOUNDED
        if isinstance(r, ir.Primitive):
            return 2 * SIZES.get(r.name, 1) - 1
        if isinstance(r, ir.String):
            return 3 + 4 + r.bound + 1 if r.bound else UNBOUNDED
        if isinstance(r, ir.Sequence):
            if not r.bound:
                return UNBOUNDED
            return min(UNBOUNDED, 7 + r.bound * self.max_size(r.element, depth + 1))
        if isinstance(r, ir.Array):
            return min(UNBOUNDED, math.prod(r.dims) * self.max_size(r.element, depth + 1))
        d = self.decl(r)
        if isinstance(d, ir.Enum):
            return 2 * enum_size(d) - 1
        if not isinstance(d, (ir.Struct, ir.Union)):
            return UNBOUNDED
        known = self._max.get(d.scoped_name)
        if known is not None:
            return known
        if isinstance(d, ir.Struct):
            size = min(UNBOUNDED, sum(self.max_size(m.type, depth + 1) for m in self.model.all_members(d)))
        else:
            size = min(UNBOUNDED, self.max_size(d.discriminator, depth + 1)
                       + max((self.max_size(c.member.type, depth + 1) for c in d.cases), default=0))
        # A finite size is exact; UNBOUNDED may be the depth cut's when reached below the top.
        if size < UNBOUNDED or depth == 0:
            self._max[d.scoped_name] = size
        return size

    # -- statements -------------------------------------------------------------------
    def _var(self) -> str:
        self._loop += 1
        return f"i{self._loop}"

    def encode(self, t: ir.Type, expr: str, what: str) -> list[str]:
        """Statements writing `expr` (of type t) to Writer `w`."""
        r = self.real(t)
        if isinstance(r, ir.Primitive):
            return [f"w.put_bool({expr});" if r.name == "boolean" else f"w.template put<{PRIMITIVES[r.name]}>({expr});"]
        if isinstance(r, ir.String):
            return [f"w.put_string({expr}, {r.bound or 0}u, {cpp_str(what)});"]
        if isinstance(r, ir.Sequence):
            head = f"w.put_count({expr}.size(), {r.bound or 0}u, {cpp_str(what)});"
            if self._bulk(r.element):
                return [head, f"w.put_array({expr}.data(), {expr}.size());"]
            i = self._var()
            return [head, f"for (std::size_t {i} = 0; {i} < {expr}.size(); ++{i}) {{",
                    *("    " + s for s in self.encode(r.element, f"{expr}[{i}]", what)), "}"]
        if isinstance(r, ir.Array):
            if len(r.dims) == 1 and self._bulk(r.element):
                return [f"w.put_array({expr}.data(), {r.dims[0]});"]
            i = self._var()
            inner = ir.Array(r.element, r.dims[1:]) if len(r.dims) > 1 else r.element
            return [f"for (std::size_t {i} = 0; {i} < {r.dims[0]}; ++{i}) {{",
                    *("    " + s for s in self.encode(inner, f"{expr}[{i}]", what)), "}"]
        d = self.decl(r)
        if isinstance(d, ir.Enum):
            return [f"w.template put<{ENUM_TYPES[enum_size(d)]}>(static_cast<{ENUM_TYPES[enum_size(d)]}>({expr}));"]
        return [f"encode(w, {expr});"]

    def decode(self, t: ir.Type, lhs: str, what: str, enum_check: Callable[[ir.Enum], str]) -> list[str]:
        """Statements reading into lvalue `lhs` (of type t) from Reader `r`."""
        r = self.real(t)
        if isinstance(r, ir.Primitive):
            return [f"{lhs} = r.get_bool();" if r.name == "boolean" else f"{lhs} = r.template get<{PRIMITIVES[r.name]}>();"]
        if isinstance(r, ir.String):
            return [f"r.get_string({lhs}, {r.bound or 0}u, {cpp_str(what)});"]
        if isinstance(r, ir.Sequence):
            if self._bulk(r.element):
                return [f"r.get_vector({lhs}, {r.bound or 0}u, {cpp_str(what)});"]
            i = self._var()
            head = (f"{lhs}.resize(r.get_count({r.bound or 0}u, {self.min_size(r.element)}u, "
                    f"{cpp_str(what)}));")
            return [head, f"for (std::size_t {i} = 0; {i} < {lhs}.size(); ++{i}) {{",
                    *("    " + s for s in self.decode(r.element, f"{lhs}[{i}]", what, enum_check)), "}"]
        if isinstance(r, ir.Array):
            if len(r.dims) == 1 and self._bulk(r.element):
                return [f"r.get_array({lhs}.data(), {r.dims[0]});"]
            i = self._var()
            inner = ir.Array(r.element, r.dims[1:]) if len(r.dims) > 1 else r.element
            return [f"for (std::size_t {i} = 0; {i} < {r.dims[0]}; ++{i}) {{",
                    *("    " + s for s in self.decode(inner, f"{lhs}[{i}]", what, enum_check)), "}"]
        d = self.decl(r)
        if isinstance(d, ir.Enum):
            return [f"{lhs} = {enum_check(d)}(r.template get<{ENUM_TYPES[enum_size(d)]}>(), r);"]
        return [f"decode(r, {lhs});"]

    def _bulk(self, t: ir.Type) -> bool:
        """Numbers copied as a block (bools are checked one by one; std::vector<bool> has no data())."""
        r = self.real(t)
        return isinstance(r, ir.Primitive) and r.name in PRIMITIVES and r.name != "boolean"
