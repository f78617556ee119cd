"""Non-default sample values for generated Python types, built from the IR.

`Filler(model, package_module)` makes a value of any IR type with the generated classes:
every string filled (with non-ASCII text), sequences of several elements, sequences of
unions walking through every branch, enums away from their first value, numbers away
from zero (float32 values exactly representable, so they compare equal after a round
trip). `plain()` turns a value into JSON-able data and `differences()` compares two such
values field by field. Used by the round-trip test and by both sides of the live test.
"""
from __future__ import annotations

import dataclasses
import enum
import glob
import importlib
import os

from rapidgen.model import ir

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GENERATED_RAPID = os.path.join(REPO, "generated", "rapid", "python")
RAPID_PACKAGE = "rapid_types"


def rapid_model() -> ir.Model:
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.idl.load import load_idl

    sink = DiagnosticSink()
    files = sorted(glob.glob(os.path.join(REPO, "specs", "rapid", "*.idl")))
    model, _ = load_idl(files, [os.path.join(REPO, "specs", "rapid")], sink)
    assert model is not None, [str(d.message) for d in sink.diagnostics]
    return model


def message_types(model: ir.Model) -> list[ir.Struct]:
    """Every RAPID message: the structs deriving from rapid::Message."""
    return [d for d in model.declarations if isinstance(d, ir.Struct) and d.base == "rapid::Message"]


def topic_of(model: ir.Model, struct: ir.Struct) -> str:
    """The message's topic constant ('rapid_imagesensor_sample' for ImageSensorSample)."""
    want = struct.name.lower()
    for d in model.declarations:
        if isinstance(d, ir.Const) and isinstance(d.value, str) and d.name.endswith("_TOPIC") \
                and d.value.startswith("rapid_") and d.value[6:].replace("_", "") == want:
            return d.value
    raise LookupError(f"no topic constant for {struct.scoped_name}")


class Filler:
    def __init__(self, model: ir.Model, package: str = RAPID_PACKAGE) -> None:
        self.model = model
        self.package = package

    def cls(self, scoped_name: str):
        parts = scoped_name.split("::")
        module = importlib.import_module(".".join([self.package, *parts[:-1]]))
        return getattr(module, parts[-1])

    def message(self, struct: ir.Struct, seed: int = 1):
        return self.make(ir.TypeRef(struct.scoped_name, "struct"), seed)

    def make(self, t: ir.Type, seed: int):
        if isinstance(t, ir.Primitive):
            return self._primitive(t.name, seed)
        if isinstance(t, ir.String):
            text = f"s{seed}-\u00e9\u00df"  # non-ASCII, 2 bytes each in UTF-8
            return text[: max(0, (t.bound or 64) - 4)]
        if isinstance(t, ir.Sequence):
            return [self.make(t.element, seed * 7 + i) for i in range(self._length(t))]
        if isinstance(t, ir.Array):
            return self._array(t.element, t.dims, seed)
        if isinstance(t, ir.TypeRef):
            d = self.model.get(t.name)
            if isinstance(d, ir.Typedef):
                return self.make(d.type, seed)
            if isinstance(d, ir.Enum):
                return list(self.cls(d.scoped_name))[(seed + 1) % len(d.enumerators)]
            if isinstance(d, ir.Struct):
                cls = self.cls(d.scoped_name)
                members = self.model.all_members(d)
                fields = dataclasses.fields(cls)
                return cls(**{f.name: self.make(m.type, seed * 3 + i) for i, (f, m) in enumerate(zip(fields, members))})
            if isinstance(d, ir.Union):
                return self._union(d, seed)
        raise TypeError(f"no filler for {t}")

    def _length(self, t: ir.Sequence) -> int:
        real = self.model.resolve_alias(t.element)
        elem = self.model.get(real.name) if isinstance(real, ir.TypeRef) else None
        if isinstance(elem, ir.Union):  # every branch appears
            want = len(elem.cases)
        elif isinstance(real, ir.Primitive) and real.name == "octet":
            want = 100_000  # big enough to be fragmented on the wire
        else:
            want = 3
        return min(t.bound or want, want)

    def _array(self, element: ir.Type, dims: tuple[int, ...], seed: int):
        if len(dims) == 1:
            return [self.make(element, seed * 5 + i) for i in range(dims[0])]
        return [self._array(element, dims[1:], seed * 5 + i) for i in range(dims[0])]

    def _union(self, u: ir.Union, seed: int):
        cls = self.cls(u.scoped_name)
        cases = [c for c in u.cases if not c.is_default] or list(u.cases)
        case = cases[seed % len(cases)]
        label = case.labels[0] if case.labels else None
        if isinstance(label, ir.EnumValue):
            label = self.cls(label.enum)[label.name]
        elif label is None:  # the default branch: a discriminator value no case names
            named = {lab for c in u.cases for lab in c.labels}
            label = next(v for v in range(1000) if v not in named)
        return cls(discriminator=label, value=self.make(case.member.type, seed))

    @staticmethod
    def _primitive(name: str, seed: int):
        if name == "boolean":
            return seed % 2 == 0
        if name in ("float32", "float64"):
            return (seed % 1000) + 0.25 if name == "float32" else seed * 1.5 + 0.1
        if name == "char8":
            return chr(65 + seed % 26)
        lo, hi = ir.INTEGER_RANGES[name]
        if lo < 0:
            value = -(seed * 131 + 7)
            return max(lo, value)
        return min(hi, seed * 37 + 3) if name != "octet" else (seed * 37 + 3) % 256


def plain(value):
    """JSON-able form of a generated value: dataclasses as dicts, unions as
    {"discriminator", "value"}, enums by name, byte strings as lists."""
    from cyclonedds.idl import IdlUnion

    if isinstance(value, IdlUnion):
        d, v = value.get()
        return {"discriminator": plain(d), "value": plain(v)}
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, enum.Enum):
        return f"{type(value).__name__}.{value.name}"
    if isinstance(value, (bytes, bytearray)):
        return list(value)
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value


def differences(expected, actual, path: str = "") -> list[str]:
    """Field-by-field comparison of two plain() values; one line per difference."""
    if isinstance(expected, dict) and isinstance(actual, dict):
        out = []
        for key in expected.keys() | actual.keys():
            if key not in actual or key not in expected:
                out.append(f"{path}.{key}: {'missing' if key not in actual else 'unexpected'}")
            else:
                out += differences(expected[key], actual[key], f"{path}.{key}")
        return sorted(out)
    if isinstance(expected, list) and isinstance(actual, list):
        if len(expected) != len(actual):
            return [f"{path}: length {len(actual)}, expected {len(expected)}"]
        out = []
        for i, (e, a) in enumerate(zip(expected, actual)):
            out += differences(e, a, f"{path}[{i}]")
        return out
    if type(expected) is not type(actual) or expected != actual:
        return [f"{path}: {actual!r}, expected {expected!r}"]
    return []
