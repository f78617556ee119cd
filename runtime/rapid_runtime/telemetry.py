"""Telemetry helpers: each declared telemetry entry's values, in its config's order,
checked against the declared DataTypes; rates; the config a sample pairs with."""
from __future__ import annotations

import time

from rapid_runtime.values import coerce, shape_error


class TelemetryError(ValueError):
    """A value that does not fit its declared key (unknown key, wrong type)."""


def ordered_values(keys: list[dict], values: dict) -> list[tuple[str, object]]:
    """(DataType, value) per declared key, in declaration order (Config.valueKeys[i]
    describes values[i]); a key not given keeps its declared default (or the type's zero)."""
    unknown = set(values) - {k["name"] for k in keys}
    if unknown:
        raise TelemetryError(f"undeclared value key(s): {', '.join(sorted(map(str, unknown)))}")
    out = []
    for k in keys:
        dtype = k["type"]
        if k["name"] in values:
            v = coerce(dtype, values[k["name"]])
        else:
            v = coerce(dtype, k["default"]) if k.get("has_default") else zero(dtype)
        why = shape_error(dtype, v)
        if why:
            raise TelemetryError(f"value {k['name']}: {why} (declared {dtype})")
        out.append((dtype, v))
    return out


def typed_values(values: dict | None) -> list[tuple[str, str, object]]:
    """(key, DataType, value) per entry of a free key -> value mapping (image extras): a value
    given as (DataType, value) keeps its type; otherwise bool is RAPID_BOOL, int RAPID_INT
    (RAPID_LONGLONG past 32 bits), float RAPID_DOUBLE, str RAPID_STRING, 3 numbers
    RAPID_VEC3d, 9 numbers RAPID_MAT33f."""
    out = []
    for key, v in (values or {}).items():
        if isinstance(v, tuple) and len(v) == 2 and isinstance(v[0], str) and v[0].startswith("RAPID_"):
            dtype, v = v
        elif isinstance(v, bool):
            dtype = "RAPID_BOOL"
        elif isinstance(v, int):
            dtype = "RAPID_INT" if -(1 << 31) <= v < (1 << 31) else "RAPID_LONGLONG"
        elif isinstance(v, float):
            dtype = "RAPID_DOUBLE"
        elif isinstance(v, str):
            dtype = "RAPID_STRING"
        elif isinstance(v, (list, tuple)) and len(v) in (3, 9):
            dtype = "RAPID_VEC3d" if len(v) == 3 else "RAPID_MAT33f"
        else:
            raise TelemetryError(f"value {key}: no DataType for {v!r} (give it as (DataType, value))")
        try:
            v = coerce(dtype, v)
        except (TypeError, ValueError) as exc:
            raise TelemetryError(f"value {key}: {exc}") from None
        why = shape_error(dtype, v)
        if why:
            raise TelemetryError(f"value {key}: {why} ({dtype})")
        out.append((str(key), dtype, v))
    return out


def zero(dtype: str) -> object:
    return {"RAPID_BOOL": False, "RAPID_STRING": "", "RAPID_INT": 0, "RAPID_LONGLONG": 0,
            "RAPID_VEC3d": [0.0] * 3, "RAPID_MAT33f": [0.0] * 9}.get(dtype, 0.0)


class Rate:
    """Whether a sample is due at the declared rate (Hz; None: only on change)."""

    def __init__(self, hz: float | None, clock=time.monotonic) -> None:
        self.period = 1.0 / hz if hz else None
        self.clock = clock
        self.next = 0.0

    def due(self) -> bool:
        if self.period is None:
            return False
        now = self.clock()
        if now < self.next:
            return False
        self.next = max(self.next + self.period, now)
        return True
