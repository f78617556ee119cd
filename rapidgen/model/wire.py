"""Wire sizes every target agrees on: primitive sizes, enum widths, the fewest bytes a value
takes in XCDR1 (decoders refuse a count the bytes left cannot hold), and the largest XCDR1
encoding of a struct's key (big-endian, from offset 0), which decides whether the RTPS key
hash is the key bytes themselves (16 or fewer) or their MD5."""
from __future__ import annotations

import math

from rapidgen.model import ir

PRIMITIVE_SIZES = {"int8": 1, "uint8": 1, "int16": 2, "uint16": 2, "int32": 4, "uint32": 4, "int64": 8,
                   "uint64": 8, "float32": 4, "float64": 8, "char8": 1, "boolean": 1, "octet": 1}
KEY_HASH_BYTES = 16  # a key whose largest encoding fits is hashed as its bytes, else MD5
KEY_UNBOUNDED = 1 << 20  # "no bound": past any size a key hash cares about
MAX_DEPTH = 50


def enum_size(e: ir.Enum) -> int:
    return 1 if e.bit_bound <= 8 else 2 if e.bit_bound <= 16 else 4


def align(offset: int, n: int) -> int:
    return -(-offset // n) * n


def min_size(model: ir.Model, t: ir.Type, depth: int = 0) -> int:
    """Fewest bytes a value of t takes in XCDR1 (alignment ignored): a decoder refuses a
    count that the bytes left cannot hold before it allocates anything."""
    return _min_size(model, t, depth, model.memo("wire.min_size"))[0]


def _min_size(model: ir.Model, t: ir.Type, depth: int, memo: dict) -> tuple[int, int, bool]:
    """(size, levels below `depth` it looked, whether MAX_DEPTH cut it short). A struct's or
    union's size is remembered when nothing cut it short, and reused wherever its levels
    fit under MAX_DEPTH again: the same value, computed once."""
    r = model.resolve_alias(t)
    if depth > MAX_DEPTH:
        return 0, 0, True
    if isinstance(r, ir.Primitive):
        return PRIMITIVE_SIZES.get(r.name, 1), 0, False
    if isinstance(r, ir.String):
        return 5, 0, False  # length and terminating NUL
    if isinstance(r, ir.Sequence):
        return 4, 0, False
    if isinstance(r, ir.Array):
        size, below, cut = _min_size(model, r.element, depth + 1, memo)
        return math.prod(r.dims) * size, below + 1, cut
    d = model.get(r.name) if isinstance(r, ir.TypeRef) else None
    if isinstance(d, ir.Enum):
        return enum_size(d), 0, False
    if isinstance(d, (ir.Struct, ir.Union)):
        known = memo.get(d.scoped_name)
        if known is not None and depth + known[1] <= MAX_DEPTH:
            return known[0], known[1], False
        parts = ([_min_size(model, m.type, depth + 1, memo) for m in model.all_members(d)] if isinstance(d, ir.Struct)
                 else [_min_size(model, d.discriminator, depth + 1, memo)])
        size = sum(p[0] for p in parts)
        below = 1 + max((p[1] for p in parts), default=0) if parts else 0
        cut = any(p[2] for p in parts)
        if not cut:
            memo[d.scoped_name] = (size, below)
        return size, below, cut
    return 0, 0, False


def key_end(model: ir.Model, t: ir.Type, offset: int, depth: int = 0) -> int:
    """Where the largest encoding of t written at `offset` ends; KEY_UNBOUNDED or more when
    it has no bound. Alignment is monotonic, so aligning the largest offset bounds every
    smaller one: exact for fixed-size keys."""
    r = model.resolve_alias(t)
    if offset >= KEY_UNBOUNDED or depth > MAX_DEPTH:
        return KEY_UNBOUNDED
    if isinstance(r, ir.Primitive):
        n = PRIMITIVE_SIZES.get(r.name, 1)
        return align(offset, n) + n
    if isinstance(r, ir.String):
        return align(offset, 4) + 4 + r.bound + 1 if r.bound else KEY_UNBOUNDED
    if isinstance(r, (ir.Sequence, ir.Array)):
        if isinstance(r, ir.Sequence):
            if not r.bound:
                return KEY_UNBOUNDED
            count, offset = r.bound, align(offset, 4) + 4
        else:
            count = math.prod(r.dims)
        for _ in range(count):
            end = key_end(model, r.element, offset, depth + 1)
            if end == offset or end >= KEY_UNBOUNDED:  # zero-size elements, or no bound
                return end
            offset = end
        return offset
    d = model.get(r.name) if isinstance(r, ir.TypeRef) else None
    if isinstance(d, ir.Enum):
        return align(offset, enum_size(d)) + enum_size(d)
    if isinstance(d, ir.Struct):
        for m in model.all_members(d):
            offset = key_end(model, m.type, offset, depth + 1)
        return offset
    if isinstance(d, ir.Union):
        start = key_end(model, d.discriminator, offset, depth + 1)
        return max([start] + [key_end(model, c.member.type, start, depth + 1) for c in d.cases])
    return KEY_UNBOUNDED


def key_max_size(model: ir.Model, key_types: list[ir.Type]) -> int:
    """The largest encoding of a key whose members (in key order) have these types."""
    end = 0
    for t in key_types:
        end = key_end(model, t, end)
    return min(end, KEY_UNBOUNDED)
