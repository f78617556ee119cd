"""The reference XCDR1/XCDR2 encoder: a value in the value form -> bytes (no header).

Use it through `rapidgen.cdr` (which adds the encapsulation header). The rules it
implements are listed in docs/cdr-and-vectors.md; every byte it writes follows from the
Model alone.
"""
from __future__ import annotations

import math
import struct
from collections.abc import Sequence
from decimal import Decimal, InvalidOperation

from rapidgen.model import ir
from rapidgen.cdr.typeinfo import MAX_DEPTH, PRIMITIVES, CdrError, CdrTypes, MemberInfo, packer

PID_EXTENDED = 0x3F01
PID_LIST_END = 0x3F02
PID_FLAG_MU = 0x4000  # must-understand bit of the short parameter id
PID_LONG_MU = 0x40000000  # must-understand bit of the extended member id
EM_MU = 0x80000000  # must-understand bit of an XCDR2 EMHEADER

# element types a list may hold for the packed fast path (others are checked one by one)
_FAST_KINDS: dict[str, tuple[type, ...]] = {
    **{k: (int,) for k in ("int8", "uint8", "octet", "int16", "uint16", "int32", "uint32", "int64", "uint64")},
    "float32": (float, int), "float64": (float, int), "boolean": (bool,),
}
_INT_FORMATS = {"int8", "uint8", "octet", "int16", "uint16", "int32", "uint32", "int64", "uint64"}


def float128_bytes(x: float, little: bool) -> bytes:
    """The IEEE 754 binary128 value equal to the double `x` (every double is exact)."""
    if math.isnan(x):
        bits = (0x7FFF << 112) | (1 << 111)
    else:
        sign = 1 if math.copysign(1.0, x) < 0 else 0
        a = abs(x)
        if math.isinf(a):
            bits = (sign << 127) | (0x7FFF << 112)
        elif a == 0:
            bits = sign << 127
        else:
            m, e = math.frexp(a)  # a = m * 2**e, 0.5 <= m < 1
            mant = int(m * (1 << 53))  # 53 significant bits, top bit set
            shift = mant.bit_length() - 1
            frac = (mant - (1 << shift)) << (112 - shift)
            bits = (sign << 127) | ((e - 1 + 16383) << 112) | frac
    return bits.to_bytes(16, "little" if little else "big")


class Encoder:
    def __init__(self, types: CdrTypes, version: int, little: bool, origin: int = 0) -> None:
        self.t = types
        self.v = version
        self.little = little
        self.e = "<" if little else ">"
        self.buf = bytearray()
        self.origin = origin  # alignment is counted from here
        self.maxalign = 8 if version == 1 else 4
        self.depth = 0

    # -- low level ----------------------------------------------------------------------
    def align(self, n: int) -> None:
        n = min(n, self.maxalign)
        pad = (self.origin - len(self.buf)) % n
        if pad:
            self.buf += bytes(pad)

    def put(self, fmt: str, size: int, value: object) -> None:
        self.align(size)
        try:
            self.buf += packer(self.e + fmt).pack(value)
        except (struct.error, OverflowError) as exc:
            raise self.fail(f"cannot encode {value!r}: {exc}") from None

    def u32(self, value: int) -> None:
        self.put("I", 4, value)

    def reserve_u32(self) -> int:
        self.align(4)
        pos = len(self.buf)
        self.buf += bytes(4)
        return pos

    def patch_u32(self, pos: int, value: int) -> None:
        if value > 0xFFFFFFFF:
            raise CdrError("encoded length does not fit in 32 bits", pos)
        packer(self.e + "I").pack_into(self.buf, pos, value)

    def fail(self, message: str) -> CdrError:
        return CdrError(message, len(self.buf))

    def enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise self.fail(f"value nests deeper than {MAX_DEPTH} levels")

    # -- dispatch -------------------------------------------------------------------------
    def value(self, t: ir.Type, v: object) -> None:
        r = self.t.resolve(t)
        if isinstance(r, ir.Primitive):
            self.primitive(r.name, v)
        elif isinstance(r, ir.String):
            self.string(r, v)
        elif isinstance(r, ir.Sequence):
            self.sequence(r, v)
        elif isinstance(r, ir.Array):
            self.array(r, v)
        elif isinstance(r, ir.TypeRef):
            d = self.t.decl(r)
            if isinstance(d, ir.Struct):
                self.struct(d, v)
            elif isinstance(d, ir.Union):
                self.union(d, v)
            elif isinstance(d, ir.Enum):
                self.enum(d, v)
            elif isinstance(d, ir.Bitmask):
                self.bitmask(d, v)
            elif isinstance(d, ir.Bitset):
                self.bitset(d, v)
            else:
                raise self.fail(f"type '{r.name}' ({d.kind}) cannot be encoded")
        elif isinstance(r, ir.Map):
            self.map(r, v)
        elif isinstance(r, ir.Fixed):
            self.fixed(r, v)
        else:
            raise self.fail(f"type '{t}' cannot be encoded")

    # -- primitives -----------------------------------------------------------------------
    def check_primitive(self, name: str, v: object) -> int | float:
        """The value to pack for a primitive, after type and range checks."""
        if name in _INT_FORMATS:
            if type(v) is not int:
                raise self.fail(f"expected an integer for {name}, got {type(v).__name__}")
            lo, hi = ir.INTEGER_RANGES[name]
            if not lo <= v <= hi:
                raise self.fail(f"{v} is out of range for {name} ({lo}..{hi})")
            return v
        if name in ir.FLOAT_TYPES:
            if type(v) is not float and type(v) is not int:  # not bool
                raise self.fail(f"expected a number for {name}, got {type(v).__name__}")
            f = float(v)
            if name == "float32" and math.isfinite(f) and abs(f) >= 3.4028235677973366e38:
                raise self.fail(f"{v} is out of range for float32")
            return f
        if name == "boolean":
            if type(v) is not bool:
                raise self.fail(f"expected true or false for boolean, got {type(v).__name__}")
            return int(v)
        if name in ("char8", "char16"):
            if not isinstance(v, str) or len(v) != 1:
                raise self.fail(f"expected a one-character string for {name}")
            code = ord(v)
            if code > (0xFF if name == "char8" else 0xFFFF):
                raise self.fail(f"character U+{code:04X} does not fit in {name}")
            return code
        raise self.fail(f"unknown primitive '{name}'")

    def primitive(self, name: str, v: object) -> None:
        value = self.check_primitive(name, v)
        fmt, size = PRIMITIVES[name]
        if name == "float128":
            self.align(16)
            self.buf += float128_bytes(value, self.little)
            return
        self.put(fmt, size, value)

    def primitives(self, name: str, items: Sequence[object], n: int) -> None:
        """n primitives of one kind, packed at once."""
        if n == 0:
            return
        fmt, size = PRIMITIVES[name]
        if name == "octet" and isinstance(items, (bytes, bytearray, memoryview)):
            self.buf += bytes(items)
            return
        if name == "float128":
            for i, x in enumerate(items):
                try:
                    self.primitive(name, x)
                except CdrError as err:
                    raise err.within(f"[{i}]") from None
            return
        self.align(size)
        kinds = _FAST_KINDS.get(name)
        if kinds is not None and all(type(x) in kinds for x in items):
            try:  # struct checks the ranges; on failure, find the culprit below
                self.buf += packer(f"{self.e}{n}{fmt}").pack(*items)
                return
            except (struct.error, OverflowError):
                pass
        values = []
        for i, x in enumerate(items):
            try:
                values.append(self.check_primitive(name, x))
            except CdrError as err:
                raise err.within(f"[{i}]") from None
        try:
            self.buf += packer(f"{self.e}{n}{fmt}").pack(*values)
        except (struct.error, OverflowError) as exc:
            raise self.fail(f"cannot encode {name} values: {exc}") from None

    # -- strings ----------------------------------------------------------------------------
    def string(self, r: ir.String, v: object) -> None:
        if not isinstance(v, str):
            raise self.fail(f"expected a string, got {type(v).__name__}")
        if r.wide:
            try:
                data = v.encode("utf-16-le" if self.little else "utf-16-be")
            except UnicodeEncodeError:
                raise self.fail("wide string is not valid Unicode (lone surrogate)") from None
            if r.bound is not None and len(data) // 2 > r.bound:
                raise self.fail(f"wide string of {len(data) // 2} code units exceeds its bound {r.bound}")
            self.u32(len(data))
            self.buf += data
            return
        if "\0" in v:
            raise self.fail("string contains a NUL character")
        try:
            data = v.encode("utf-8")
        except UnicodeEncodeError:
            raise self.fail("string is not valid Unicode (lone surrogate)") from None
        if r.bound is not None and len(data) > r.bound:
            raise self.fail(f"string of {len(data)} bytes exceeds its bound {r.bound}")
        self.u32(len(data) + 1)
        self.buf += data
        self.buf.append(0)

    # -- collections -----------------------------------------------------------------------
    def begin_dheader(self, needed: bool) -> int | None:
        return self.reserve_u32() if needed else None

    def end_dheader(self, pos: int | None) -> None:
        if pos is not None:
            self.patch_u32(pos, len(self.buf) - pos - 4)

    def elements(self, elem: ir.Type, items: Sequence[object], n: int) -> None:
        r = self.t.resolve(elem)
        if isinstance(r, ir.Primitive):
            self.primitives(r.name, items, n)
            return
        for i, x in enumerate(items):
            try:
                self.value(elem, x)
            except CdrError as err:
                raise err.within(f"[{i}]") from None

    def sequence(self, r: ir.Sequence, v: object) -> None:
        if isinstance(v, (bytes, bytearray, memoryview)):
            if self.t.resolve(r.element) != ir.Primitive("octet"):
                raise self.fail(f"bytes are only accepted for sequences of octet, not {r}")
        elif not isinstance(v, (list, tuple)):
            raise self.fail(f"expected a list for {r}, got {type(v).__name__}")
        n = len(v)
        if r.bound is not None and n > r.bound:
            raise self.fail(f"sequence of {n} elements exceeds its bound {r.bound}")
        self.enter()
        dh = self.begin_dheader(self.v == 2 and not self.t.is_primitive(r.element))
        self.u32(n)
        self.elements(r.element, v, n)
        self.end_dheader(dh)
        self.depth -= 1

    def array(self, r: ir.Array, v: object) -> None:
        dims, elem = self.t.array_shape(r)
        flat: list[object] = []
        self.flatten(v, dims, 0, flat, self.t.resolve(elem) == ir.Primitive("octet"))
        self.enter()
        dh = self.begin_dheader(self.v == 2 and not self.t.is_primitive(elem))
        self.elements(elem, flat, len(flat))
        self.end_dheader(dh)
        self.depth -= 1

    def flatten(self, v: object, dims: tuple[int, ...], level: int, out: list, octets: bool) -> None:
        want = dims[level]
        octet_row = octets and level == len(dims) - 1  # bytes are accepted for the last dimension
        if not isinstance(v, (list, tuple, bytes, bytearray, memoryview)) or \
                (not octet_row and not isinstance(v, (list, tuple))):
            raise self.fail(f"expected a list of {want} elements for an array, got {type(v).__name__}")
        if len(v) != want:
            raise self.fail(f"array dimension {level + 1} needs {want} elements, got {len(v)}")
        if level == len(dims) - 1:
            out.extend(v)
            return
        for i, x in enumerate(v):
            try:
                self.flatten(x, dims, level + 1, out, octets)
            except CdrError as err:
                raise err.within(f"[{i}]") from None

    def map(self, r: ir.Map, v: object) -> None:
        pairs = list(v.items()) if isinstance(v, dict) else v
        if not isinstance(pairs, (list, tuple)):
            raise self.fail(f"expected a list of [key, value] pairs for {r}")
        if r.bound is not None and len(pairs) > r.bound:
            raise self.fail(f"map of {len(pairs)} entries exceeds its bound {r.bound}")
        self.enter()
        dh = self.begin_dheader(self.v == 2 and not (self.t.is_primitive(r.key) and self.t.is_primitive(r.value)))
        self.u32(len(pairs))
        seen: set[object] = set()
        for i, pair in enumerate(pairs):
            try:
                if not isinstance(pair, (list, tuple)) or len(pair) != 2:
                    raise self.fail("a map entry must be a [key, value] pair")
                k = pair[0]
                if isinstance(k, (str, int, float, bool)):
                    if (type(k), k) in seen:
                        raise self.fail(f"duplicate map key {k!r}")
                    seen.add((type(k), k))
                self.value(r.key, k)
                self.value(r.value, pair[1])
            except CdrError as err:
                raise err.within(f"[{i}]") from None
        self.end_dheader(dh)
        self.depth -= 1

    def fixed(self, r: ir.Fixed, v: object) -> None:
        if isinstance(v, bool) or not isinstance(v, (str, int, Decimal)):
            raise self.fail("expected a decimal string for a fixed-point value")
        try:
            d = Decimal(v)
            q = d.quantize(Decimal(1).scaleb(-r.scale))
        except (InvalidOperation, ValueError):
            raise self.fail(f"{v!r} is not a decimal number") from None
        if q != d or not d.is_finite():
            raise self.fail(f"{v} has more than {r.scale} fractional digits")
        digits = str(abs(int(q.scaleb(r.scale))))
        if len(digits) > r.digits:
            raise self.fail(f"{v} has more than {r.digits} digits")
        nibbles = [int(c) for c in digits.rjust(r.digits, "0")]
        if r.digits % 2 == 0:
            nibbles.insert(0, 0)
        nibbles.append(0xD if q < 0 else 0xC)
        self.buf += bytes((nibbles[i] << 4) | nibbles[i + 1] for i in range(0, len(nibbles), 2))

    # -- enums, bitmasks, bitsets -------------------------------------------------------------
    def enum(self, d: ir.Enum, v: object) -> None:
        by_name, by_value = self.t.enum_maps(d)
        if isinstance(v, str):
            if v not in by_name:
                raise self.fail(f"'{v}' is not an enumerator of {d.scoped_name}")
            number = by_name[v]
        elif type(v) is int and v in by_value:
            number = v
        else:
            raise self.fail(f"{v!r} is not an enumerator of {d.scoped_name}")
        size = self.t.enum_size(d)
        self.put({1: "b", 2: "h", 4: "i"}[size], size, number)

    def bitmask(self, d: ir.Bitmask, v: object) -> None:
        if type(v) is not int or v < 0:
            raise self.fail(f"expected a non-negative integer mask for {d.scoped_name}")
        allowed = sum(1 << b.position for b in d.values)
        if v & ~allowed:
            raise self.fail(f"mask 0x{v:x} sets bits that {d.scoped_name} does not define")
        size = self.t.bitmask_size(d)
        self.put({1: "B", 2: "H", 4: "I", 8: "Q"}[size], size, v)

    def bitset(self, d: ir.Bitset, v: object) -> None:
        if not isinstance(v, dict):
            raise self.fail(f"expected an object of bit fields for {d.scoped_name}")
        fields = self.t.bitset_fields(d)
        names = {f.name for f in fields if f.name}
        extra = sorted(k for k in v if k not in names)
        if extra:
            raise self.fail(f"'{extra[0]}' is not a bit field of {d.scoped_name}")
        bits, shift = 0, 0
        for f in fields:
            x = v.get(f.name, 0) if f.name else 0
            if f.type.name == "boolean":
                if type(x) is not bool:
                    raise self.fail(f"bit field '{f.name}' needs true or false")
                x = int(x)
            elif type(x) is not int:
                raise self.fail(f"bit field '{f.name}' needs an integer")
            signed = f.type.name.startswith("int")
            lo, hi = (-(1 << (f.width - 1)), (1 << (f.width - 1)) - 1) if signed else (0, (1 << f.width) - 1)
            if not lo <= x <= hi:
                raise self.fail(f"{x} does not fit in the {f.width}-bit field '{f.name}'")
            bits |= (x & ((1 << f.width) - 1)) << shift
            shift += f.width
        size = self.t.bitset_size(d)
        self.put({1: "B", 2: "H", 4: "I", 8: "Q"}[size], size, bits)

    # -- structs ----------------------------------------------------------------------------
    def struct(self, d: ir.Struct, v: object) -> None:
        if not isinstance(v, dict):
            raise self.fail(f"expected an object for {d.scoped_name}, got {type(v).__name__}")
        members = self.t.members(d)
        names = {mi.member.name for mi in members}
        extra = sorted(str(k) for k in v if k not in names)
        if extra:
            raise self.fail(f"'{extra[0]}' is not a member of {d.scoped_name}")
        self.enter()
        if d.extensibility == "mutable":
            self.mutable(members, v)
        else:
            dh = self.begin_dheader(self.v == 2 and d.extensibility == "appendable")
            for mi in members:
                m = mi.member
                try:
                    if m.optional:
                        self.optional(mi, v.get(m.name))
                    elif m.name not in v:
                        raise self.fail(f"member '{m.name}' is missing")
                    else:
                        self.value(m.type, v[m.name])
                except CdrError as err:
                    raise err.within(m.name) from None
            self.end_dheader(dh)
        self.depth -= 1

    def optional(self, mi: MemberInfo, val: object) -> None:
        if self.v == 2:
            self.buf.append(0 if val is None else 1)
            if val is not None:
                self.value(mi.member.type, val)
            return
        self.parameter(mi, val, pad=False)

    def parameter(self, mi: MemberInfo, val: object, pad: bool) -> None:
        """XCDR1 parameter: extended header (PID_EXTENDED), member id, length, value."""
        self.align(4)
        self.buf += packer(self.e + "HH").pack(PID_EXTENDED | PID_FLAG_MU, 8)
        self.buf += packer(self.e + "I").pack(mi.id | (PID_LONG_MU if mi.must_understand else 0))
        lenpos = len(self.buf)
        self.buf += bytes(4)
        start = len(self.buf)
        if val is not None:
            saved, self.origin = self.origin, start  # a parameter's value aligns from its start
            try:
                self.value(mi.member.type, val)
            finally:
                self.origin = saved
            if pad:
                self.align(4)
        self.patch_u32(lenpos, len(self.buf) - start)

    def mutable(self, members: tuple[MemberInfo, ...], v: dict) -> None:
        if self.v == 1:
            for mi in members:
                m = mi.member
                if m.name not in v or (m.optional and v[m.name] is None):
                    if m.optional:
                        continue
                    raise CdrError(f"member '{m.name}' is missing", len(self.buf)).within(m.name)
                try:
                    self.parameter(mi, v[m.name], pad=True)
                except CdrError as err:
                    raise err.within(m.name) from None
            self.align(4)
            self.buf += packer(self.e + "HH").pack(PID_LIST_END | PID_FLAG_MU, 0)
            return
        dh = self.reserve_u32()
        for mi in members:
            m = mi.member
            if m.name not in v or (m.optional and v[m.name] is None):
                if m.optional:
                    continue
                raise CdrError(f"member '{m.name}' is missing", len(self.buf)).within(m.name)
            try:
                lc = self.length_code(m.type)
                self.u32((EM_MU if mi.must_understand else 0) | (lc << 28) | mi.id)
                lenpos = self.reserve_u32() if lc == 4 else None
                start = len(self.buf)
                self.value(m.type, v[m.name])
                if lenpos is not None:
                    self.patch_u32(lenpos, len(self.buf) - start)
            except CdrError as err:
                raise err.within(m.name) from None
        self.end_dheader(dh)

    def length_code(self, t: ir.Type) -> int:
        """EMHEADER length code: 0-3 fixed 1/2/4/8 bytes, 4 NEXTINT, 5-7 the value's own
        leading length (times 1, 4, 8) is the NEXTINT."""
        r = self.t.resolve(t)
        fixed = {1: 0, 2: 1, 4: 2, 8: 3}
        if isinstance(r, ir.Primitive):
            return fixed.get(PRIMITIVES[r.name][1], 4)
        if isinstance(r, ir.String):
            return 5
        if isinstance(r, ir.Sequence):
            elem = self.t.resolve(r.element)
            if isinstance(elem, ir.Primitive):
                return {1: 5, 4: 6, 8: 7}.get(PRIMITIVES[elem.name][1], 4)
            return 5  # the DHEADER counts the bytes that follow it
        if isinstance(r, ir.Array):
            _, elem = self.t.array_shape(r)
            return 4 if self.t.is_primitive(elem) else 5
        if isinstance(r, ir.TypeRef):
            d = self.t.decl(r)
            if isinstance(d, ir.Enum):
                return fixed[self.t.enum_size(d)]
            if isinstance(d, ir.Bitmask):
                return fixed[self.t.bitmask_size(d)]
            if isinstance(d, ir.Bitset):
                return fixed[self.t.bitset_size(d)]
        return 4

    # -- unions ---------------------------------------------------------------------------------
    def union(self, d: ir.Union, v: object) -> None:
        if not isinstance(v, dict) or "discriminator" not in v:
            raise self.fail(f"expected {{\"discriminator\": ..., \"value\": ...}} for {d.scoped_name}")
        extra = sorted(str(k) for k in v if k not in ("discriminator", "value"))
        if extra:
            raise self.fail(f"a union value has only 'discriminator' and 'value', not '{extra[0]}'")
        if d.extensibility == "mutable":
            raise self.fail(f"@mutable unions ({d.scoped_name}) are not supported by the reference encoder")
        disc = v["discriminator"]
        self.enter()
        dh = self.begin_dheader(self.v == 2 and d.extensibility == "appendable")
        try:
            self.value(d.discriminator, disc)
        except CdrError as err:
            raise err.within("discriminator") from None
        case = self.t.union_case(d, self.t.disc_number(d, disc))
        if case is None:
            if v.get("value") is not None:
                raise self.fail(f"discriminator {disc!r} selects no member of {d.scoped_name}, "
                                "so the value must be absent")
        else:
            if "value" not in v:
                raise self.fail(f"discriminator {disc!r} selects member '{case.member.name}': value missing")
            try:
                self.value(case.member.type, v["value"])
            except CdrError as err:
                raise err.within(case.member.name) from None
        self.end_dheader(dh)
        self.depth -= 1


__all__ = ["Encoder", "float128_bytes"]
