"""Constant-expression evaluation with IDL types.

Integers are evaluated exactly (Python ints); every intermediate result must fit in
64 bits and the final value in the target type, otherwise an overflow error is
reported. A string over its bound is an error too (RG0402), except in a const
declaration, where it is only a warning (RG0406), as with RTI's compiler. Integer division
truncates toward zero like C. Division by zero, operators on the wrong kind of operand and
type mismatches are errors with locations.
"""
from __future__ import annotations

import operator
from dataclasses import dataclass
from decimal import Decimal
from typing import Callable, NoReturn

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.idl import ast
from rapidgen.model.ir import CHAR_TYPES, FLOAT_TYPES, IDL_SPELLING, INTEGER_RANGES, ConstValue, EnumValue

_I64_MIN, _U64_MAX = -2**63, 2**64 - 1
_INT_OPS = {"+": operator.add, "-": operator.sub, "*": operator.mul, "<<": operator.lshift,
            ">>": operator.rshift, "&": operator.and_, "|": operator.or_, "^": operator.xor}


@dataclass(frozen=True, slots=True)
class Target:
    """What a constant expression must produce."""

    category: str  # int | float | fixed | char | string | bool | enum | any
    name: str = ""  # primitive name, enum scoped name, or type spelling for messages
    bound: int | None = None  # string bound
    wide: bool = False

    def describe(self) -> str:
        if self.category == "int" or self.category in ("float", "char"):
            return f"'{IDL_SPELLING.get(self.name, self.name)}'"
        if self.category == "string":
            word = "wstring" if self.wide else "string"
            return f"'{word}<{self.bound}>'" if self.bound else f"'{word}'"
        if self.category == "enum":
            return f"enum '{self.name}'"
        return {"bool": "'boolean'", "fixed": "'fixed'", "any": "a constant"}[self.category]


@dataclass(frozen=True, slots=True)
class Typed:
    category: str  # int | float | fixed | char | string | bool | enum
    value: ConstValue


class EvalError(Exception):
    """Raised after a diagnostic was reported, to abandon one expression."""


_CATEGORY_WORDS = {"int": "an integer", "float": "a floating-point number", "fixed": "a fixed-point number",
                   "char": "a character", "string": "a string", "bool": "a boolean", "enum": "an enumerator"}

NameLookup = Callable[[ast.ScopedName], "Typed | None"]


class ConstEvaluator:
    def __init__(self, sink: DiagnosticSink) -> None:
        self.sink = sink

    # -- public -------------------------------------------------------------------
    def evaluate(self, expr: ast.Expr, target: Target, lookup: NameLookup,
                 const_decl: bool = False) -> ConstValue | None:
        """The value of expr converted to target, or None after reporting an error.

        const_decl: expr is a `const` declaration's value, where a string over its bound
        is only a warning; anywhere else (e.g. a @default) the value must fit."""
        try:
            typed = self._eval(expr, lookup, target)
            return self._convert(typed, target, expr.loc, const_decl)
        except EvalError:
            return None

    # -- evaluation ---------------------------------------------------------------
    def _fail(self, code: str, message: str, loc: SourceLoc, hint: str | None = None) -> NoReturn:
        self.sink.error(code, message, loc, hint)
        raise EvalError(message)

    def _eval(self, expr: ast.Expr, lookup: NameLookup, target: Target) -> Typed:
        if isinstance(expr, ast.Literal):
            cat = {"int": "int", "float": "float", "fixed": "fixed", "char": "char", "wchar": "char",
                   "string": "string", "wstring": "string", "bool": "bool"}[expr.kind]
            return Typed(cat, expr.value)
        if isinstance(expr, ast.NameRef):
            found = lookup(expr.name)
            if found is None:
                raise EvalError("unresolved name")
            return found
        if isinstance(expr, ast.Unary):
            val = self._eval(expr.operand, lookup, target)
            return self._unary(expr, val, target)
        if isinstance(expr, ast.Binary):
            left = self._eval(expr.left, lookup, target)
            right = self._eval(expr.right, lookup, target)
            return self._binary(expr, left, right)
        self._fail("RG0401", "not a constant expression", getattr(expr, "loc", SourceLoc("<input>", 1, 1)))

    def _check64(self, value: int, loc: SourceLoc) -> int:
        if not _I64_MIN <= value <= _U64_MAX:
            self._fail("RG0402", f"integer overflow: {value} does not fit in 64 bits", loc,
                       "constant expressions are evaluated with 64-bit integers")
        return value

    def _unary(self, expr: ast.Unary, val: Typed, target: Target) -> Typed:
        number = val.value
        if expr.op in "+-" and isinstance(number, (int, float, Decimal)) and val.category in ("int", "float", "fixed"):
            v = number if expr.op == "+" else -number
            return Typed(val.category, self._check64(v, expr.loc) if isinstance(v, int) else v)
        if expr.op == "~" and isinstance(number, int) and val.category == "int":
            v = number
            if target.category == "int" and target.name in INTEGER_RANGES and INTEGER_RANGES[target.name][0] == 0:
                bits = INTEGER_RANGES[target.name][1].bit_length()
                return Typed("int", ((1 << bits) - 1) ^ v)
            return Typed("int", ~v)
        self._fail("RG0401", f"operator '{expr.op}' cannot be applied to {_CATEGORY_WORDS[val.category]}",
                   expr.loc)

    def _binary(self, expr: ast.Binary, a: Typed, b: Typed) -> Typed:
        op, loc = expr.op, expr.loc
        numeric = ("int", "float", "fixed")
        if a.category not in numeric or b.category not in numeric:
            bad = a if a.category not in numeric else b
            self._fail("RG0401", f"operator '{op}' cannot be applied to {_CATEGORY_WORDS[bad.category]}", loc)
        x, y = _number(a), _number(b)
        if isinstance(x, int) and isinstance(y, int):
            return Typed("int", self._check64(self._int_op(op, x, y, loc), loc))
        if op in ("%", "<<", ">>", "&", "|", "^"):
            self._fail("RG0401", f"operator '{op}' needs integer operands", loc)
        fn = {"+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv}[op]
        if "fixed" in (a.category, b.category) and "float" not in (a.category, b.category):
            dx, dy = Decimal(x), Decimal(y)
            if op == "/" and dy == 0:
                self._fail("RG0403", "division by zero", loc)
            return Typed("fixed", fn(dx, dy))
        fx, fy = float(x), float(y)
        if op == "/" and fy == 0:
            self._fail("RG0403", "division by zero", loc)
        return Typed("float", fn(fx, fy))

    def _int_op(self, op: str, x: int, y: int, loc: SourceLoc) -> int:
        if op in ("/", "%") and y == 0:
            self._fail("RG0403", "division by zero" if op == "/" else "remainder by zero", loc)
        if op in ("<<", ">>") and not 0 <= y < 64:
            self._fail("RG0402", f"shift count {y} is outside 0..63", loc)
        if op == "/":
            q = abs(x) // abs(y)
            return q if (x >= 0) == (y >= 0) else -q
        if op == "%":
            r = abs(x) % abs(y)
            return r if x >= 0 else -r
        return _INT_OPS[op](x, y)

    # -- conversion to the target type ------------------------------------------------
    def _convert(self, val: Typed, target: Target, loc: SourceLoc, const_decl: bool) -> ConstValue:
        cat, v = target.category, val.value
        if cat == "any":
            return v
        if cat == "int" and val.category == "int" and isinstance(v, int):
            lo, hi = INTEGER_RANGES[target.name]
            if not lo <= v <= hi:
                self._fail("RG0402", f"value {v} does not fit in {target.describe()} ({lo}..{hi})", loc)
            return int(v)
        if cat == "float" and val.category in ("int", "float") and isinstance(v, (int, float)):
            value = float(v)
            if target.name == "float32" and abs(value) > 3.4028234663852886e38 and value != float("inf"):
                self._fail("RG0402", f"value {value} does not fit in 'float'", loc)
            return value
        if cat == "fixed" and val.category in ("int", "fixed") and isinstance(v, (int, Decimal)):
            return Decimal(v)
        if cat == "char" and val.category == "char":
            if target.name == "char8" and ord(str(val.value)) > 255:
                self._fail("RG0402", "character does not fit in 'char'", loc, "use wchar for wide characters")
            return val.value
        if cat == "string" and val.category == "string":
            text = str(val.value)
            if target.bound is not None and len(text) > target.bound and not const_decl:
                self._fail("RG0402", f"string of {len(text)} characters exceeds the bound of "
                           f"{target.describe()}", loc, f"shorten it to {target.bound} characters")
            if target.bound is not None and len(text) > target.bound:
                # RAPID's own IDL has these (`const String16 K = "ATHLETE_HEADING_RAD";`) and
                # RTI's compiler accepts them: warn, and keep the whole value, as it does
                self.sink.warning("RG0406", f"string of {len(text)} characters exceeds the bound of "
                                  f"{target.describe()}; the whole value is kept", loc,
                                  f"shorten it to {target.bound} characters or widen the type")
            return text
        if cat == "bool" and val.category == "bool":
            return bool(val.value)
        if cat == "enum" and val.category == "enum":
            ev = val.value
            if isinstance(ev, EnumValue) and ev.enum == target.name:
                return ev
            other = ev.enum if isinstance(ev, EnumValue) else "?"
            self._fail("RG0401", f"'{ev}' is an enumerator of '{other}', not of '{target.name}'", loc)
        got = _CATEGORY_WORDS[val.category]
        self._fail("RG0401", f"type mismatch: {target.describe()} cannot hold {got}", loc,
                   _mismatch_hint(target, val))


def _number(val: Typed) -> int | float | Decimal:
    """An arithmetic operand (the caller checked its category is numeric)."""
    v = val.value
    assert isinstance(v, (int, float, Decimal)) and not isinstance(v, bool), val
    return v


def _mismatch_hint(target: Target, val: Typed) -> str | None:
    if target.category == "int" and val.category == "float":
        return "write an integer literal, without a decimal point"
    if target.category == "string" and val.category == "char":
        return "use double quotes for strings"
    if target.category == "enum":
        return f"use one of the enumerators of '{target.name}'"
    return None


def target_for_primitive(name: str) -> Target:
    if name in INTEGER_RANGES:
        return Target("int", name)
    if name in FLOAT_TYPES:
        return Target("float", name)
    if name in CHAR_TYPES:
        return Target("char", name)
    if name == "boolean":
        return Target("bool", name)
    return Target("any", name)
