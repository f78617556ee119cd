"""Reference XCDR1/XCDR2 encoder and decoder that work from the Model alone.

    from rapidgen.cdr import Codec, CdrError
    codec = Codec(model)
    data = codec.encode("rapid::Command", value)                 # XCDR1, little-endian, with header
    data = codec.encode("rapid::Command", value, version=2, little=False)
    value = codec.decode("rapid::Command", data)                 # the header gives version and byte order

No DDS library is involved; the golden vectors (`rapidgen vectors`) are made with it and
every language back end is held to its bytes. The value form (plain Python/JSON data)
and the wire rules are described in docs/cdr-and-vectors.md. In short:

- struct: dict of member name -> value, base members included, in wire order; an absent
  @optional member is None (or left out when encoding)
- union: {"discriminator": D, "value": V}; no "value" when D selects no member
- enum: the enumerator's name (encoding also takes its integer value)
- sequence, array: list (nested lists for multi-dimensional arrays); octets as lists of
  int (encoding also takes bytes)
- string, wstring, char, wchar: str; boolean: bool; integers: int; floats: float
- bitmask: int; bitset: dict of field -> int/bool; map: list of [key, value];
  fixed: decimal str ("12.50")

The decoder treats its input as untrusted: any bytes give a value or a `CdrError`
(message, offset), never another exception, an allocation beyond the input's size or a hang.
"""
from __future__ import annotations

from dataclasses import dataclass

from rapidgen.model import ir
from rapidgen.cdr.decode import Decoder
from rapidgen.cdr.encode import Encoder
from rapidgen.cdr.typeinfo import CdrError, CdrTypes

__all__ = ["CdrError", "Codec", "Encapsulation", "ENCAPSULATIONS", "decode", "encode", "encapsulation_id"]


@dataclass(frozen=True)
class Encapsulation:
    name: str
    version: int  # 1: XCDR1, 2: XCDR2
    little: bool
    extensibility: tuple[str, ...]  # the type kinds it is used for


# RTPS/XTypes encapsulation identifiers (the first two bytes, big-endian on the wire).
ENCAPSULATIONS: dict[int, Encapsulation] = {
    0x0000: Encapsulation("CDR_BE", 1, False, ("final", "appendable")),
    0x0001: Encapsulation("CDR_LE", 1, True, ("final", "appendable")),
    0x0002: Encapsulation("PL_CDR_BE", 1, False, ("mutable",)),
    0x0003: Encapsulation("PL_CDR_LE", 1, True, ("mutable",)),
    0x0006: Encapsulation("CDR2_BE", 2, False, ("final",)),
    0x0007: Encapsulation("CDR2_LE", 2, True, ("final",)),
    0x0008: Encapsulation("D_CDR2_BE", 2, False, ("appendable",)),
    0x0009: Encapsulation("D_CDR2_LE", 2, True, ("appendable",)),
    0x000A: Encapsulation("PL_CDR2_BE", 2, False, ("mutable",)),
    0x000B: Encapsulation("PL_CDR2_LE", 2, True, ("mutable",)),
}

MAX_TRAILING = 3  # padding a writer may leave after the value (options record it)


def encapsulation_id(extensibility: str, version: int, little: bool) -> int:
    for ident, enc in ENCAPSULATIONS.items():
        if enc.version == version and enc.little == little and extensibility in enc.extensibility:
            return ident
    raise CdrError(f"no encapsulation for a {extensibility} type in XCDR{version}")


class Codec:
    """Encoder and decoder for the types of one Model (caches what it learns about them)."""

    def __init__(self, model: ir.Model) -> None:
        self.model = model
        self.types = CdrTypes(model)

    def encode(self, type_spec: str | ir.Type, value: object, *, version: int = 1, little: bool = True,
               header: bool = True) -> bytes:
        """Encode `value` of the type (scoped name or type expression) as XCDR1 or XCDR2."""
        if version not in (1, 2):
            raise CdrError(f"XCDR version must be 1 or 2, not {version}")
        t = self.types.type_of(type_spec)
        enc = Encoder(self.types, version, little, origin=4 if header else 0)
        if header:
            ident = encapsulation_id(self.types.extensibility(t), version, little)
            enc.buf += bytes((ident >> 8, ident & 0xFF, 0, 0))
        try:
            enc.value(t, value)
        except RecursionError:
            raise CdrError("value nests too deeply", len(enc.buf)) from None
        return bytes(enc.buf)

    def header_of(self, data: bytes) -> Encapsulation:
        if len(data) < 4:
            raise CdrError(f"truncated: {len(data)} bytes cannot hold the 4-byte encapsulation header", 0)
        ident = (data[0] << 8) | data[1]
        enc = ENCAPSULATIONS.get(ident)
        if enc is None:
            raise CdrError(f"unknown encapsulation identifier 0x{ident:04x}", 0)
        return enc

    def decode(self, type_spec: str | ir.Type, data: bytes | bytearray | memoryview, *, header: bool = True,
               version: int | None = None, little: bool | None = None) -> object:
        """Decode one value. With a header, it gives the version and byte order (and must
        suit the type's extensibility); without one, pass `version` and `little`."""
        data = bytes(data)
        t = self.types.type_of(type_spec)
        if header:
            enc = self.header_of(data)
            ext = self.types.extensibility(t)
            if ext not in enc.extensibility:
                raise CdrError(f"encapsulation {enc.name} does not suit a @{ext} type", 0)
            if (version is not None and version != enc.version) or (little is not None and little != enc.little):
                raise CdrError(f"encapsulation {enc.name} contradicts the requested encoding", 0)
            version, little, start = enc.version, enc.little, 4
        else:
            if version not in (1, 2) or little is None:
                raise CdrError("without a header, give version (1 or 2) and little (True/False)")
            start = 0
        dec = Decoder(self.types, data, start, version, little)
        try:
            value = dec.value(t)
        except RecursionError:
            raise CdrError("data nests too deeply", dec.pos) from None
        trailing = len(data) - dec.pos
        if trailing > MAX_TRAILING:
            raise CdrError(f"{trailing} bytes left after the end of the value", dec.pos)
        return value


_last: tuple[ir.Model, Codec] | None = None


def _codec(model: ir.Model) -> Codec:
    global _last
    if _last is None or _last[0] is not model:
        _last = (model, Codec(model))
    return _last[1]


def encode(model: ir.Model, type_spec: str | ir.Type, value: object, **options) -> bytes:
    """`Codec(model).encode(...)`, reusing the codec of the last model."""
    return _codec(model).encode(type_spec, value, **options)


def decode(model: ir.Model, type_spec: str | ir.Type, data: bytes, **options) -> object:
    """`Codec(model).decode(...)`, reusing the codec of the last model."""
    return _codec(model).decode(type_spec, data, **options)
