"""Type-level rules resolved once, for the IR to store: member ids, enum and union defaults.

Every consumer (the codec, each back end, the asset checks) reads the stored facts
(`Member.member_id`, `Enum.default`, `Union.default_discriminator`/`default_case`) and
never works them out again, so they cannot disagree on the wire.
"""
from __future__ import annotations

import hashlib

from rapidgen.model import ir


def name_hash(text: str) -> int:
    """XTypes member id of a name: the first 4 bytes of its MD5, little-endian, 28 bits.

    Raises UnicodeEncodeError for text with no UTF-8 form (a lone surrogate)."""
    return int.from_bytes(hashlib.md5(text.encode("utf-8")).digest()[:4], "little") & ir.MEMBER_ID_MASK


class MemberIds:
    """The member ids of one declaring type, in declaration order (XTypes 7.3.1.2.1.1):
    @id, else @hashid's text (or the name) hashed, else under @autoid(HASH) the name
    hashed, else the previous id + 1. A derived struct goes on from its base's last id."""

    def __init__(self, autoid: ir.AutoId, inherited: tuple[ir.Member, ...] = ()) -> None:
        self.hashed = autoid == "HASH"
        self.next = inherited[-1].member_id + 1 if inherited else 0

    def take(self, name: str, explicit: int | None, hashid: str | None) -> int:
        if explicit is not None:
            mid = explicit
        elif hashid is not None:
            mid = name_hash(hashid or name)
        elif self.hashed:
            mid = name_hash(name)
        else:
            mid = self.next
        self.next = mid + 1
        return mid & ir.MEMBER_ID_MASK


def enum_default(enumerators: tuple[ir.Enumerator, ...]) -> tuple[str, bool]:
    """(the enumerator an enum defaults to, whether @default_literal chose it)."""
    for e in enumerators:
        if any(a.name == "default_literal" for a in e.annotations):
            return e.name, True
    return (enumerators[0].name if enumerators else ""), False


def discriminator_default(real: ir.Type, enum: ir.Enum | None) -> ir.Label:
    """The default value of a discriminator type (typedefs already followed)."""
    if enum is not None:
        e = enum.default_enumerator
        return ir.EnumValue(enum.scoped_name, e.name, e.value) if e else 0
    if isinstance(real, ir.Primitive) and real.name == "boolean":
        return False
    if isinstance(real, ir.Primitive) and real.name in ir.CHAR_TYPES:
        return "\0"
    return 0


def union_default(cases: tuple[ir.UnionCase, ...], disc: ir.Label) -> int | None:
    """The case a union's default discriminator selects: the one labelled with it, else
    the `default:` case, else none."""
    key = ir.label_key(disc)
    for i, c in enumerate(cases):
        if any(ir.label_key(lab) == key for lab in c.labels):
            return i
    return next((i for i, c in enumerate(cases) if c.is_default), None)
