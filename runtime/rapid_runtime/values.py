"""RAPID DataType values: shape (what the ParameterUnion member can carry), then the
descriptor's limits (range, allowed values). Each check returns None or a short reason."""
from __future__ import annotations

import math

from rapid_runtime import texts

INT32 = (-2**31, 2**31 - 1)
INT64 = (-2**63, 2**63 - 1)
FLOAT32_MAX = 3.4028234663852886e38
STRING_BYTES = 127  # ParameterUnion.s is a String128
COUNTS = {"RAPID_VEC3d": 3, "RAPID_MAT33f": 9}
# DataType -> ParameterUnion member (rapid-protocol.md section 2)
MEMBER = {"RAPID_BOOL": "b", "RAPID_DOUBLE": "d", "RAPID_FLOAT": "f", "RAPID_INT": "i", "RAPID_LONGLONG": "ll",
          "RAPID_STRING": "s", "RAPID_VEC3d": "vec3d", "RAPID_MAT33f": "mat33f"}
DATA_TYPES = tuple(MEMBER)


def _number(v: object) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def shape_error(dtype: str, value: object) -> str | None:
    """Why value cannot be a `dtype` ParameterUnion, or None."""
    if dtype == "RAPID_BOOL":
        return None if isinstance(value, bool) else "not a boolean"
    if dtype in ("RAPID_INT", "RAPID_LONGLONG"):
        lo, hi = INT32 if dtype == "RAPID_INT" else INT64
        if not isinstance(value, int) or isinstance(value, bool):
            return "not an integer"
        return None if lo <= value <= hi else f"{value} does not fit {'32' if dtype == 'RAPID_INT' else '64'} bits"
    if dtype in ("RAPID_FLOAT", "RAPID_DOUBLE"):
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            return "not a number"
        if dtype == "RAPID_FLOAT" and math.isfinite(value) and abs(value) > FLOAT32_MAX:
            return "out of float range"
        return None
    if dtype == "RAPID_STRING":
        if not isinstance(value, str):
            return "not a string"
        n = len(value.encode("utf-8", "surrogatepass"))
        return None if n <= STRING_BYTES else texts.string_too_long(n, STRING_BYTES)
    if dtype in COUNTS:
        if not isinstance(value, (list, tuple)) or len(value) != COUNTS[dtype]:
            return f"needs {COUNTS[dtype]} numbers"
        if not all(_number(x) for x in value):
            return "holds a non-number"
        if dtype == "RAPID_MAT33f" and any(math.isfinite(x) and abs(x) > FLOAT32_MAX for x in value):
            return "out of float range"
        return None
    return f"unknown DataType {dtype}"


def _fmt(x: object) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


def limit_error(param, value: object) -> str | None:
    """Why value is outside param's range or allowed values (param: tables.Param), or None.
    NaN is outside every range; a range applies to each element of a vector."""
    if param.allowed and value not in param.allowed:
        shown = "|".join(str(a) for a in param.allowed)
        return texts.not_one_of(repr(value), shown)
    if param.min is None and param.max is None:
        return None
    items = value if isinstance(value, (list, tuple)) else [value]
    for x in items:
        if not isinstance(x, (int, float)) or isinstance(x, bool):
            continue
        if math.isnan(x) or (param.min is not None and x < param.min) or (param.max is not None and x > param.max):
            lo = "-inf" if param.min is None else _fmt(param.min)
            hi = "inf" if param.max is None else _fmt(param.max)
            return texts.out_of_range(_fmt(x), lo, hi)
    return None


def coerce(dtype: str, value: object) -> object:
    """A value a handler or commander gave, in the form the DataType carries (ints where
    floats are wanted become floats; tuples become lists). Shape is checked separately."""
    if dtype in ("RAPID_FLOAT", "RAPID_DOUBLE") and isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    if dtype in COUNTS and isinstance(value, (list, tuple)):
        return [float(x) if _number(x) else x for x in value]
    return value


def parse_text(dtype: str, text: str) -> object:
    """A command-line argument (`key=value`) as a `dtype` value; ValueError when it is not one."""
    t = text.strip()
    if dtype == "RAPID_BOOL":
        low = t.lower()
        if low in ("true", "1", "yes", "on"):
            return True
        if low in ("false", "0", "no", "off"):
            return False
        raise ValueError(f"{text!r} is not a boolean (true/false)")
    if dtype in ("RAPID_INT", "RAPID_LONGLONG"):
        return int(t, 0)
    if dtype in ("RAPID_FLOAT", "RAPID_DOUBLE"):
        return float(t)
    if dtype == "RAPID_STRING":
        return text
    if dtype in COUNTS:
        parts = [p for p in t.strip("[]()").replace(" ", ",").split(",") if p]
        return [float(p) for p in parts]
    raise ValueError(f"unknown DataType {dtype}")
