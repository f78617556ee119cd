"""A decoded DDS sample as JSON-ready data: one rule for every tool that shows or forwards
samples as JSON (the ROS 2 ground node's config topics, `rapidgen spy` and its echo, the
monitor), so the same sample reads the same everywhere:

- a struct: an object of its IDL member names, in declaration order;
- an enum: its enumerator's name ("RAPID_DOUBLE");
- a union: {"discriminator": ..., "value": ...} (the discriminator plain too: an enum's
  name, else its number), the form the generated tables write unions in, so a config's JSON
  reads back as its tables' computed value;
- octets (bytes): lowercase hex, two digits a byte ("00ff"), compact where an image's data
  as a list of numbers would be megabytes;
- NaN and infinities: the strings "NaN", "Infinity", "-Infinity" (JSON has no such
  numbers; these are JavaScript's spellings);
- sequences and arrays: lists; str, int, bool, finite floats and None as they are;
  anything else its str().
"""
from __future__ import annotations

import dataclasses
import enum
import math
from typing import Any


def plain(value: Any) -> Any:
    """`value` (a cyclonedds IdlStruct, IdlUnion, enum, sequence or scalar) as JSON-ready data."""
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, float):
        if math.isfinite(value):
            return value
        return "NaN" if value != value else ("Infinity" if value > 0 else "-Infinity")
    if value is None or isinstance(value, (str, int)):
        return value
    if isinstance(value, (bytes, bytearray)):
        return bytes(value).hex()
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if hasattr(value, "discriminator") and hasattr(value, "value"):  # an IdlUnion
        return {"discriminator": plain(value.discriminator), "value": plain(value.value)}
    return str(value)
