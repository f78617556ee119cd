"""The reference XCDR1/XCDR2 decoder: bytes -> a value in the value form.

The bytes are untrusted. Every length is checked against the bytes that are left (and
against the type's bound) before anything is allocated; nesting is limited; every
failure is a `CdrError` with the offset. Use it through `rapidgen.cdr`.
"""
from __future__ import annotations

import math
import struct
from decimal import Decimal

from rapidgen.model import ir
from rapidgen.cdr.typeinfo import (MAX_DEPTH, MAX_EMPTY_ELEMENTS, MAX_VALUES_BASE, PRIMITIVES, VALUES_PER_BYTE,
                                      CdrError, CdrTypes, MemberInfo, format_fixed, packer)

_PID_MASK = 0x3FFF
_PID_EXTENDED = 0x3F01
_PID_LIST_END = 0x3F02
_PID_IGNORE = 0x3F03
_PID_MU = 0x4000
_LONG_MU = 0x40000000
_LONG_ID = 0x0FFFFFFF


def float128_value(raw: bytes, little: bool) -> float:
    """The double nearest to an IEEE 754 binary128 value."""
    bits = int.from_bytes(raw, "little" if little else "big")
    sign = -1.0 if bits >> 127 else 1.0
    exp = (bits >> 112) & 0x7FFF
    frac = bits & ((1 << 112) - 1)
    if exp == 0x7FFF:
        return math.nan if frac else sign * math.inf
    if exp == 0:
        return sign * 0.0 if frac == 0 else sign * math.ldexp(float(frac), -16382 - 112)
    try:
        return sign * math.ldexp(float((1 << 112) | frac), exp - 16383 - 112)
    except OverflowError:
        return sign * math.inf


class Decoder:
    def __init__(self, types: CdrTypes, data: bytes, pos: int, version: int, little: bool) -> None:
        self.t = types
        self.data = data
        self.pos = pos
        self.end = len(data)  # reads stop here (a DHEADER or a parameter narrows it)
        self.origin = pos
        self.v = version
        self.little = little
        self.e = "<" if little else ">"
        self.maxalign = 8 if version == 1 else 4
        self.depth = 0
        # values this input may still make: memory stays in proportion to its length
        self.size = max(0, len(data) - pos)
        self.allowance = MAX_VALUES_BASE + VALUES_PER_BYTE * self.size
        self.budget = self.allowance

    # -- low level ----------------------------------------------------------------------
    def fail(self, message: str, at: int | None = None) -> CdrError:
        return CdrError(message, self.pos if at is None else at)

    def need(self, n: int) -> None:
        if n > self.end - self.pos:
            left = self.end - self.pos
            raise self.fail(f"truncated: need {n} byte{'s' * (n != 1)}, {left} left")

    def align(self, n: int) -> None:
        n = min(n, self.maxalign)
        pad = (self.origin - self.pos) % n
        if pad:
            self.need(pad)
            self.pos += pad

    def get(self, fmt: str, size: int) -> int | float:
        """One primitive of a struct format: a float for 'f'/'d', an int otherwise."""
        self.align(size)
        self.need(size)
        value: int | float = packer(self.e + fmt).unpack_from(self.data, self.pos)[0]
        self.pos += size
        return value

    def get_int(self, fmt: str, size: int) -> int:
        """One integer (fmt is an integer format)."""
        self.align(size)
        self.need(size)
        value: int = packer(self.e + fmt).unpack_from(self.data, self.pos)[0]
        self.pos += size
        return value

    def u32(self) -> int:
        return self.get_int("I", 4)

    def charge(self, n: int, what: str) -> None:
        """Spend n values of the budget before making them."""
        if n > self.budget:
            raise self.fail(f"{what} would make the value hold more than {self.allowance} values, "
                            f"the most {self.size} bytes may decode to")
        self.budget -= n

    def default(self, t: ir.Type, name: str) -> object:
        """The default of an absent member, charged to the budget first."""
        self.charge(self.t.default_count(t), f"the default of absent member '{name}'")
        return self.t.default_value(t)

    def enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise self.fail(f"data nests deeper than {MAX_DEPTH} levels")
        self.charge(1, "one more aggregate")

    def check_count(self, n: int, elem: ir.Type, what: str) -> None:
        """Before allocating n elements: do the bytes left hold them at all?"""
        smallest = self.t.min_size(elem, self.v)
        left = self.end - self.pos
        if smallest == 0:
            if n > MAX_EMPTY_ELEMENTS:
                raise self.fail(f"{what} of {n} elements is more than {MAX_EMPTY_ELEMENTS} empty elements")
        elif n > left // smallest:
            raise self.fail(f"{what} of {n} elements needs at least {n * smallest} bytes, {left} left")
        self.charge(n, f"{what} of {n} elements")

    def open_dheader(self) -> int:
        """Read a DHEADER; reads are limited to its length. Returns the previous limit."""
        size = self.u32()
        if size > self.end - self.pos:
            raise self.fail(f"DHEADER length {size} exceeds the {self.end - self.pos} bytes left", self.pos - 4)
        saved, self.end = self.end, self.pos + size
        return saved

    def close_dheader(self, saved: int, exact: bool) -> None:
        if exact and self.pos != self.end:
            raise self.fail(f"{self.end - self.pos} bytes left inside a DHEADER")
        self.pos = self.end
        self.end = saved

    # -- dispatch -------------------------------------------------------------------------
    def value(self, t: ir.Type) -> object:
        r = self.t.resolve(t)
        if isinstance(r, ir.Primitive):
            return self.primitive(r.name)
        if isinstance(r, ir.String):
            return self.string(r)
        if isinstance(r, ir.Sequence):
            return self.sequence(r)
        if isinstance(r, ir.Array):
            return self.array(r)
        if isinstance(r, ir.TypeRef):
            d = self.t.decl(r)
            if isinstance(d, ir.Struct):
                return self.struct(d)
            if isinstance(d, ir.Union):
                return self.union(d)
            if isinstance(d, ir.Enum):
                return self.enum(d)
            if isinstance(d, ir.Bitmask):
                return self.bitmask(d)
            if isinstance(d, ir.Bitset):
                return self.bitset(d)
            raise self.fail(f"type '{r.name}' ({d.kind}) cannot be decoded")
        if isinstance(r, ir.Map):
            return self.map(r)
        if isinstance(r, ir.Fixed):
            return self.fixed(r)
        raise self.fail(f"type '{t}' cannot be decoded")

    # -- primitives -----------------------------------------------------------------------
    def primitive(self, name: str) -> object:
        fmt, size = PRIMITIVES[name]
        if name == "float128":
            self.align(16)
            self.need(16)
            raw = self.data[self.pos:self.pos + 16]
            self.pos += 16
            return float128_value(raw, self.little)
        self.align(size)
        at = self.pos
        if name == "boolean":
            x = self.get_int(fmt, size)
            if x > 1:
                raise self.fail(f"boolean byte is {x}, not 0 or 1", at)
            return x == 1
        if name in ("char8", "char16"):
            return chr(self.get_int(fmt, size))
        return self.get(fmt, size)

    def primitives(self, name: str, n: int) -> list:
        if n == 0:
            return []
        fmt, size = PRIMITIVES[name]
        if name == "float128":
            return [self.primitive(name) for _ in range(n)]
        self.align(size)
        self.need(n * size)
        at = self.pos
        if size == 1:
            raw = self.data[self.pos:self.pos + n]
            self.pos += n
            if name == "boolean":
                bad = next((i for i, b in enumerate(raw) if b > 1), None)
                if bad is not None:
                    raise self.fail(f"boolean byte is {raw[bad]}, not 0 or 1", at + bad)
                return [b == 1 for b in raw]
            if name == "char8":
                return [chr(b) for b in raw]
            if name == "int8":
                return list(struct.unpack(f"{n}b", raw))
            return list(raw)
        values = list(packer(f"{self.e}{n}{fmt}").unpack_from(self.data, self.pos))
        self.pos += n * size
        if name == "char16":
            return [chr(c) for c in values]
        return values

    # -- strings ----------------------------------------------------------------------------
    def string(self, r: ir.String) -> str:
        self.align(4)
        at = self.pos
        n = self.u32()
        if r.wide:
            if n % 2:
                raise self.fail(f"wide string length {n} is odd", at)
            if r.bound is not None and n // 2 > r.bound:
                raise self.fail(f"wide string of {n // 2} code units exceeds its bound {r.bound}", at)
            self.need(n)
            raw = self.data[self.pos:self.pos + n]
            self.pos += n
            try:
                return raw.decode("utf-16-le" if self.little else "utf-16-be")
            except UnicodeDecodeError:
                raise self.fail("wide string is not valid UTF-16", at) from None
        if n == 0:
            raise self.fail("string length 0: the length must count the NUL terminator", at)
        if r.bound is not None and n - 1 > r.bound:
            raise self.fail(f"string of {n - 1} bytes exceeds its bound {r.bound}", at)
        self.need(n)
        raw = self.data[self.pos:self.pos + n - 1]
        if self.data[self.pos + n - 1] != 0:
            raise self.fail("string is not NUL-terminated", self.pos + n - 1)
        if 0 in raw:
            raise self.fail("string contains a NUL byte before its end", self.pos + raw.index(0))
        self.pos += n
        try:
            return raw.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise self.fail(f"string is not valid UTF-8 ({exc.reason})", at + 4 + exc.start) from None

    # -- collections -----------------------------------------------------------------------
    def elements(self, elem: ir.Type, n: int) -> list:
        r = self.t.resolve(elem)
        if isinstance(r, ir.Primitive):
            return self.primitives(r.name, n)
        out = []
        for i in range(n):
            try:
                out.append(self.value(elem))
            except CdrError as err:
                raise err.within(f"[{i}]") from None
        return out

    def sequence(self, r: ir.Sequence) -> list:
        self.enter()
        saved = self.open_dheader() if self.v == 2 and not self.t.is_primitive(r.element) else None
        self.align(4)
        at = self.pos
        n = self.u32()
        if r.bound is not None and n > r.bound:
            raise self.fail(f"sequence of {n} elements exceeds its bound {r.bound}", at)
        self.check_count(n, r.element, "sequence")
        out = self.elements(r.element, n)
        if saved is not None:
            self.close_dheader(saved, exact=True)
        self.depth -= 1
        return out

    def array(self, r: ir.Array) -> list:
        dims, elem = self.t.array_shape(r)
        self.enter()
        saved = self.open_dheader() if self.v == 2 and not self.t.is_primitive(elem) else None
        total = 1
        for d in dims:
            total *= d
        self.check_count(total, elem, "array")
        flat = self.elements(elem, total)
        if saved is not None:
            self.close_dheader(saved, exact=True)
        self.depth -= 1
        return _shape(flat, dims)

    def map(self, r: ir.Map) -> list:
        self.enter()
        dh = self.v == 2 and not (self.t.is_primitive(r.key) and self.t.is_primitive(r.value))
        saved = self.open_dheader() if dh else None
        self.align(4)
        at = self.pos
        n = self.u32()
        if r.bound is not None and n > r.bound:
            raise self.fail(f"map of {n} entries exceeds its bound {r.bound}", at)
        smallest = self.t.min_size(r.key, self.v) + self.t.min_size(r.value, self.v)
        if (smallest and n > (self.end - self.pos) // smallest) or (not smallest and n > MAX_EMPTY_ELEMENTS):
            raise self.fail(f"map of {n} entries does not fit in the {self.end - self.pos} bytes left", at)
        self.charge(2 * n, f"map of {n} entries")
        out = []
        seen: set[object] = set()
        for i in range(n):
            try:
                k = self.value(r.key)
                if isinstance(k, (str, int, float, bool)):
                    if (type(k), k) in seen:
                        raise self.fail(f"duplicate map key {k!r}")
                    seen.add((type(k), k))
                out.append([k, self.value(r.value)])
            except CdrError as err:
                raise err.within(f"[{i}]") from None
        if saved is not None:
            self.close_dheader(saved, exact=True)
        self.depth -= 1
        return out

    def fixed(self, r: ir.Fixed) -> str:
        size = (r.digits + 2) // 2
        self.need(size)
        at = self.pos
        raw = self.data[self.pos:self.pos + size]
        self.pos += size
        nibbles = [x for b in raw for x in (b >> 4, b & 0xF)]
        sign = nibbles.pop()
        if sign not in (0xC, 0xD):
            raise self.fail(f"fixed-point sign nibble 0x{sign:x} is not 0xc or 0xd", at + size - 1)
        if any(x > 9 for x in nibbles):
            raise self.fail("fixed-point digit nibble above 9", at)
        number = int("".join(map(str, nibbles)) or "0")
        value = Decimal(-number if sign == 0xD else number).scaleb(-r.scale)
        return format_fixed(value, r.scale)

    # -- enums, bitmasks, bitsets -------------------------------------------------------------
    def enum(self, d: ir.Enum) -> str:
        size = self.t.enum_size(d)
        self.align(size)
        at = self.pos
        number = self.get_int({1: "b", 2: "h", 4: "i"}[size], size)
        _, by_value = self.t.enum_maps(d)
        if number not in by_value:
            raise self.fail(f"{number} is not a value of enum {d.scoped_name}", at)
        return by_value[number]

    def bitmask(self, d: ir.Bitmask) -> int:
        size = self.t.bitmask_size(d)
        self.align(size)
        at = self.pos
        mask = self.get_int({1: "B", 2: "H", 4: "I", 8: "Q"}[size], size)
        allowed = sum(1 << b.position for b in d.values)
        if mask & ~allowed:
            raise self.fail(f"mask 0x{mask:x} sets bits that {d.scoped_name} does not define", at)
        return mask

    def bitset(self, d: ir.Bitset) -> dict:
        size = self.t.bitset_size(d)
        bits = self.get_int({1: "B", 2: "H", 4: "I", 8: "Q"}[size], size)
        out: dict[str, object] = {}
        shift = 0
        for f in self.t.bitset_fields(d):
            x = (bits >> shift) & ((1 << f.width) - 1)
            shift += f.width
            if not f.name:
                continue
            if f.type.name == "boolean":
                out[f.name] = bool(x)
            elif f.type.name.startswith("int") and x >> (f.width - 1):
                out[f.name] = x - (1 << f.width)
            else:
                out[f.name] = x
        return out

    # -- structs ----------------------------------------------------------------------------
    def struct(self, d: ir.Struct) -> dict:
        members = self.t.members(d)
        self.enter()
        if d.extensibility == "mutable":
            out = self.mutable(d, members)
        else:
            appendable = self.v == 2 and d.extensibility == "appendable"
            saved = self.open_dheader() if appendable else None
            out = {}
            for mi in members:
                m = mi.member
                if appendable and self.pos >= self.end:  # an older writer's shorter type
                    out[m.name] = None if m.optional else self.default(m.type, m.name)
                    continue
                try:
                    out[m.name] = self.optional(mi) if m.optional else self.value(m.type)
                except CdrError as err:
                    raise err.within(m.name) from None
            if saved is not None:
                self.close_dheader(saved, exact=False)  # a newer writer's members are skipped
        self.depth -= 1
        return out

    def optional(self, mi: MemberInfo) -> object:
        if self.v == 2:
            at = self.pos
            self.need(1)
            flag = self.data[self.pos]
            self.pos += 1
            if flag > 1:
                raise self.fail(f"optional flag is {flag}, not 0 or 1", at)
            return self.value(mi.member.type) if flag else None
        pid, mid, length, _ = self.parameter_header()
        if pid in (_PID_LIST_END, _PID_IGNORE) or mid != mi.id:
            raise self.fail(f"expected the parameter of member id {mi.id}, found id {mid}")
        if length == 0:
            return None
        return self.parameter_value(mi, length)

    def parameter_header(self) -> tuple[int, int, int, bool]:
        """(short pid, member id, length, must understand) of an XCDR1 parameter."""
        self.align(4)
        self.need(4)
        pid, length = packer(self.e + "HH").unpack_from(self.data, self.pos)
        self.pos += 4
        short = pid & _PID_MASK
        if short == _PID_EXTENDED:
            at = self.pos
            if length != 8:
                raise self.fail(f"PID_EXTENDED with length {length}, not 8", at - 2)
            self.need(8)
            mid, length = packer(self.e + "II").unpack_from(self.data, self.pos)
            self.pos += 8
            return short, mid & _LONG_ID, length, bool(mid & _LONG_MU)
        return short, short, length, bool(pid & _PID_MU)

    def parameter_value(self, mi: MemberInfo, length: int) -> object:
        if length > self.end - self.pos:
            raise self.fail(f"parameter length {length} exceeds the {self.end - self.pos} bytes left")
        start = self.pos
        saved_end, saved_origin = self.end, self.origin
        self.end, self.origin = start + length, start
        try:
            value = self.value(mi.member.type)
        finally:
            self.end, self.origin = saved_end, saved_origin
        self.pos = start + length
        return value

    def mutable(self, d: ir.Struct, members: tuple[MemberInfo, ...]) -> dict:
        by_id = {mi.id: mi for mi in members}
        got: dict[str, object] = {}
        if self.v == 1:
            while True:
                at = self.pos
                pid, mid, length, mu = self.parameter_header()
                if pid == _PID_LIST_END:
                    break
                mi = by_id.get(mid) if pid != _PID_IGNORE else None
                if mi is None:
                    if mu:
                        raise self.fail(f"unknown must-understand member id {mid} in {d.scoped_name}", at)
                    self.need(length)
                    self.pos += length
                    continue
                if mi.member.name in got:
                    raise self.fail(f"member id {mid} appears twice", at)
                try:
                    got[mi.member.name] = self.parameter_value(mi, length)
                except CdrError as err:
                    raise err.within(mi.member.name) from None
        else:
            saved = self.open_dheader()
            while self.pos < self.end:
                at = self.pos
                if (self.origin - self.pos) % 4 >= self.end - self.pos:
                    self.pos = self.end  # only padding left
                    break
                header = self.u32()
                lc = (header >> 28) & 7
                mid = header & _LONG_ID
                if lc < 4:
                    size = 1 << lc
                elif lc == 4:
                    size = self.u32()
                else:
                    self.need(4)
                    nextint = packer(self.e + "I").unpack_from(self.data, self.pos)[0]
                    size = 4 + nextint * {5: 1, 6: 4, 7: 8}[lc]
                if size > self.end - self.pos:
                    raise self.fail(f"member length {size} exceeds the {self.end - self.pos} bytes left", at)
                mi = by_id.get(mid)
                if mi is None:
                    if header & 0x80000000:
                        raise self.fail(f"unknown must-understand member id {mid} in {d.scoped_name}", at)
                    self.pos += size
                    continue
                if mi.member.name in got:
                    raise self.fail(f"member id {mid} appears twice", at)
                start = self.pos
                limit, self.end = self.end, start + size
                try:
                    got[mi.member.name] = self.value(mi.member.type)
                except CdrError as err:
                    raise err.within(mi.member.name) from None
                finally:
                    self.end = limit
                if lc < 4 and self.pos != start + size:
                    raise self.fail(f"member '{mi.member.name}' is not {size} bytes long", start)
                self.pos = start + size
            self.close_dheader(saved, exact=True)
        out: dict[str, object] = {}
        for mi in members:
            m = mi.member
            if m.name in got:
                out[m.name] = got[m.name]
            elif m.key:
                raise self.fail(f"key member '{m.name}' of {d.scoped_name} is missing")
            else:
                out[m.name] = None if m.optional else self.default(m.type, m.name)
        return out

    # -- unions ---------------------------------------------------------------------------------
    def union(self, d: ir.Union) -> dict:
        if d.extensibility == "mutable":
            raise self.fail(f"@mutable unions ({d.scoped_name}) are not supported by the reference decoder")
        self.enter()
        appendable = self.v == 2 and d.extensibility == "appendable"
        saved = self.open_dheader() if appendable else None
        try:
            disc = self.value(d.discriminator)
        except CdrError as err:
            raise err.within("discriminator") from None
        case = self.t.union_case(d, self.t.disc_number(d, disc))
        out: dict[str, object] = {"discriminator": disc}
        if case is not None:
            try:
                out["value"] = self.value(case.member.type)
            except CdrError as err:
                raise err.within(case.member.name) from None
        if saved is not None:
            self.close_dheader(saved, exact=False)
        self.depth -= 1
        return out


def _shape(flat: list, dims: tuple[int, ...]) -> list:
    if len(dims) == 1:
        return flat
    step = len(flat) // dims[0] if dims[0] else 0
    return [_shape(flat[i * step:(i + 1) * step], dims[1:]) for i in range(dims[0])]


__all__ = ["Decoder", "float128_value"]
