"""Telemetry helpers: each declared telemetry entry's values, in its config's order,
checked against the declared DataTypes; rates; the config a sample pairs with; how long a
source may be silent before its entry is stale."""
from __future__ import annotations

import threading
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


# ---- stale telemetry (docs/runtime.md, "Stale telemetry") ----------------------------------
# An entry's bound: its descriptor's stale_after_ms, else STALE_PERIODS periods of its rate but
# at least STALE_FLOOR_MS; an entry with neither (published on change) is not watched.
STALE_PERIODS = 3
STALE_FLOOR_MS = 1000.0
# The agent value key the runtime fills with the silent entries' names (", "-separated; ""
# when every watched source is current), when the agent entry declares it as RAPID_STRING.
STALE_KEY = "stale_telemetry"


def stale_after_ms(entry: dict) -> float | None:
    """The entry's staleness bound in ms (None: not watched)."""
    declared = entry.get("stale_after_ms")
    if declared:
        return float(declared)
    rate = entry.get("rate")
    if rate:
        return max(STALE_PERIODS * 1000.0 / float(rate), STALE_FLOOR_MS)
    return None


class Freshness:
    """Per watched entry (by name) its bound and the newest source time of a sample let out.
    A sample older than its entry's bound is refused; an entry whose newest source time is older
    than its bound is silent until a current sample comes. Times in seconds since the epoch
    (the samples' stamps are wall-clock microseconds)."""

    def __init__(self, clock=time.time) -> None:
        self.clock = clock
        self.bounds: dict[str, float] = {}
        self.newest: dict[str, float] = {}
        self.silent: set[str] = set()
        self.lock = threading.Lock()

    def watch(self, name: str, bound_ms: float) -> None:
        self.bounds[name] = bound_ms / 1000.0

    def offer(self, name: str, stamp: float) -> tuple[bool, bool]:
        """(whether a sample of that source time may go out, whether its entry is back from
        silence with it). Unwatched entries always may."""
        bound = self.bounds.get(name)
        if bound is None:
            return True, False
        with self.lock:
            if self.clock() - stamp > bound:
                return False, False
            self.newest[name] = max(stamp, self.newest.get(name, stamp))
            back = name in self.silent
            self.silent.discard(name)
            return True, back

    def check(self) -> list[tuple[str, float]]:
        """(name, seconds since its newest source time) of each entry newly silent."""
        now, out = self.clock(), []
        with self.lock:
            for name, newest in self.newest.items():
                if name not in self.silent and now - newest > self.bounds[name]:
                    self.silent.add(name)
                    out.append((name, now - newest))
        return out

    def silent_names(self) -> list[str]:
        with self.lock:
            return sorted(self.silent)
