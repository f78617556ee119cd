"""Byte layouts worked out by hand from the XTypes 1.3 rules, for small types of
idl/Kitchen.idl: the reference encoder must write exactly these bytes, and decode them back."""
from __future__ import annotations

import pytest


def h(text: str) -> bytes:
    return bytes.fromhex(text.replace(" ", ""))


CASES = [
    # (type, value, version, little, expected bytes incl. the encapsulation header)
    # long long after an octet: XCDR1 aligns it to 8, XCDR2 to 4
    ("kt::OctLL", {"a": 1, "b": 0x0102030405060708}, 1, True, "0001 0000  01 000000 00000000  0807060504030201"),
    ("kt::OctLL", {"a": 1, "b": 0x0102030405060708}, 2, True, "0007 0000  01 000000  0807060504030201"),
    ("kt::OctLL", {"a": 1, "b": 0x0102030405060708}, 1, False, "0000 0000  01 000000 00000000  0102030405060708"),
    ("kt::OctLL", {"a": 1, "b": 0x0102030405060708}, 2, False, "0006 0000  01 000000  0102030405060708"),
    # strings: length counts the NUL
    ("kt::Str", {"s": "hi"}, 1, True, "0001 0000  03000000 686900"),
    ("kt::Str", {"s": ""}, 2, False, "0006 0000  00000001 00"),
    ("kt::Str", {"s": "éé"}, 1, True, "0001 0000  05000000 c3a9c3a9 00"),
    # sequences of primitives: no DHEADER in either version
    ("kt::SeqShort", {"v": [1, 2, 3]}, 2, True, "0007 0000  03000000 0100 0200 0300"),
    ("kt::SeqShort", {"v": []}, 1, False, "0000 0000  00000000"),
    # multi-dimensional array of primitives: row-major, no length, no DHEADER
    ("kt::Arr", {"a": [[1, 2, 3], [4, 5, 6]]}, 2, True, "0007 0000  0100 0200 0300 0400 0500 0600"),
    # unions: discriminator, then the selected member aligned as usual
    ("kt::U", {"discriminator": 1, "value": -2}, 1, True, "0001 0000  01000000 00000000 feffffffffffffff"),
    ("kt::U", {"discriminator": 1, "value": -2}, 2, True, "0007 0000  01000000 feffffffffffffff"),
    ("kt::U", {"discriminator": 3, "value": "ab"}, 1, True, "0001 0000  03000000 03000000 616200"),
    ("kt::U", {"discriminator": 9, "value": 200}, 1, True, "0001 0000  09000000 c8"),  # default branch
    ("kt::NoDefault", {"discriminator": 0}, 2, True, "0007 0000  0000"),  # no member selected
    ("kt::ByBool", {"discriminator": True, "value": 1.5}, 1, True, "0001 0000  01 000000 00000000 000000000000f83f"),
    ("kt::ByBool", {"discriminator": True, "value": 1.5}, 2, True, "0007 0000  01 000000 000000000000f83f"),
    ("kt::ByChar", {"discriminator": "a", "value": 2}, 1, True, "0001 0000  61 00 0200"),
    # sequence of structs: XCDR2 puts a DHEADER (byte length) before the count
    ("kt::SeqStruct", {"items": [{"a": 1, "b": 2}]}, 1, True,
     "0001 0000  01000000  01 000000  0200000000000000"),
    ("kt::SeqStruct", {"items": [{"a": 1, "b": 2}]}, 2, True,
     "0007 0000  10000000  01000000  01 000000  0200000000000000"),
    # sequence of enums: enums are not primitive, so XCDR2 has a DHEADER too
    ("kt::Colors", {"c": ["GREEN"]}, 1, True, "0001 0000  01000000 01000000"),
    ("kt::Colors", {"c": ["GREEN"]}, 2, True, "0007 0000  08000000 01000000 01000000"),
    # appendable: D_CDR2 header and a DHEADER in XCDR2; laid out as final in XCDR1
    ("kt::App", {"a": 5, "s": "xy"}, 2, True, "0009 0000  0b000000  0500 0000 03000000 787900"),
    ("kt::App", {"a": 5, "s": "xy"}, 2, False, "0008 0000  0000000b  0005 0000 00000003 787900"),
    ("kt::App", {"a": 5, "s": "xy"}, 1, True, "0001 0000  0500 0000 03000000 787900"),
    ("kt::AppU", {"discriminator": 1, "value": 5}, 2, True, "0009 0000  08000000  01 000000 05000000"),
    # mutable, XCDR2: DHEADER, then per member EMHEADER (M flag on the key, length code,
    # member id) and NEXTINT where the length code asks for it
    ("kt::Mut", {"id": 7, "x": -1, "s": "k"}, 2, True,
     "000b 0000  1a000000  000000a0 07000000  01000010 ffff 0000  02000050 02000000 6b00"),
    ("kt::Mut", {"id": 7, "x": -1, "s": "k"}, 2, False,
     "000a 0000  0000001a  a0000000 00000007  10000001 ffff 0000  50000002 00000002 6b00"),
    # mutable, XCDR1: PL_CDR with extended parameter headers (PID_EXTENDED|M, 8, id, length),
    # values aligned from the parameter's start, lengths padded to 4, then PID_LIST_END
    ("kt::Mut", {"id": 7, "x": -1, "s": "k"}, 1, True,
     "0003 0000  017f0800 00000040 04000000 07000000  017f0800 01000000 04000000 ffff0000"
     "  017f0800 02000000 08000000 02000000 6b000000  027f0000"),
    # optional members: XCDR2 a presence byte, XCDR1 a parameter (length 0 when absent)
    ("kt::Opt", {"a": 1, "b": 5}, 2, True, "0007 0000  01 01 0000 05000000"),
    ("kt::Opt", {"a": 1, "b": None}, 2, True, "0007 0000  01 00"),
    ("kt::Opt", {"a": 1, "b": 5}, 1, True, "0001 0000  01 000000 017f0800 01000000 04000000 05000000"),
    ("kt::Opt", {"a": 1, "b": None}, 1, True, "0001 0000  01 000000 017f0800 01000000 00000000"),
    # enums and bitmasks sized by @bit_bound; bitsets packed from the least significant bit
    ("kt::Small", "S2", 2, True, "0007 0000  02"),
    ("kt::Small", "S2", 1, True, "0001 0000  02"),
    ("kt::Color", "BLUE", 1, False, "0000 0000  00000002"),
    ("kt::Flags", 0x803, 2, True, "0007 0000  0308"),
    ("kt::Bits", {"a": 5, "f": True, "s": -2, "t": 33}, 2, True, "0007 0000  ed84"),
    # map: count, then key/value pairs; XCDR2 DHEADER because the key is a string
    ("kt::WithMap", {"m": [["a", 1]]}, 1, True, "0001 0000  01000000 02000000 6100 0000 01000000"),
    ("kt::WithMap", {"m": [["a", 1]]}, 2, True, "0007 0000  10000000 01000000 02000000 6100 0000 01000000"),
    # long double: 16 bytes IEEE binary128, aligned like a double (8 in XCDR1, 4 in XCDR2)
    ("kt::LD", {"a": 1, "x": 1.0}, 1, True, "0001 0000  01 000000 00000000  0000000000000000000000000000ff3f"),
    ("kt::LD", {"a": 1, "x": -2.5}, 2, False, "0006 0000  01 000000  c0004000000000000000000000000000"),
]


@pytest.mark.parametrize("type_name, value, version, little, expected", CASES,
                         ids=[f"{c[0]}-v{c[2]}-{'le' if c[3] else 'be'}-{i}" for i, c in enumerate(CASES)])
def test_hand_computed_layout(kt, type_name, value, version, little, expected):
    data = kt.encode(type_name, value, version=version, little=little)
    assert data.hex(" ", 4) == h(expected).hex(" ", 4)
    assert kt.decode(type_name, data) == value


def test_fixed_point_is_packed_bcd(kitchen_model):
    from rapidgen.model import ir
    from rapidgen.cdr import Codec

    codec = Codec(kitchen_model)
    t = ir.Fixed(5, 2)
    assert codec.encode(t, "-12.34", header=False).hex() == "01234d"
    assert codec.encode(t, "123.45", header=False).hex() == "12345c"
    assert codec.encode(ir.Fixed(4, 1), "7.5", header=False).hex() == "00075c"  # even digits: leading 0 nibble
    assert codec.decode(t, bytes.fromhex("01234d"), header=False, version=1, little=True) == "-12.34"


def test_wstring_counts_bytes_without_terminator(kt):
    from rapidgen.model import ir

    t = ir.String(5, wide=True)
    assert kt.encode(t, "aΩ", header=False).hex() == "040000006100a903"
    assert kt.encode(t, "aΩ", header=False, little=False).hex() == "00000004006103a9"
    assert kt.decode(t, bytes.fromhex("040000006100a903"), header=False, version=2, little=True) == "aΩ"


def test_member_ids_follow_id_and_hashid(kt):
    d = kt.model.get("kt::Hashed")
    ids = [mi.id for mi in kt.types.members(d)]
    from rapidgen.idl.facts import name_hash

    assert ids == [name_hash("first"), name_hash("other")]
    mut_all = [mi.id for mi in kt.types.members(kt.model.get("kt::MutAll"))]
    assert mut_all == [10, 20, 30, 40, 50, 51, 52, 53]
    child = [(mi.member.name, mi.id, mi.must_understand) for mi in kt.types.members(kt.model.get("kt::MutChild"))]
    assert child == [("id", 0, True), ("x", 1, False), ("s", 2, False), ("extra", 3, False)]


@pytest.mark.parametrize("version, little, ident", [(1, False, "0000"), (1, True, "0001"), (2, False, "0006"),
                                                    (2, True, "0007")])
def test_final_headers(kt, version, little, ident):
    assert kt.encode("kt::Str", {"s": ""}, version=version, little=little)[:4].hex() == ident + "0000"


@pytest.mark.parametrize("type_name, value, idents", [
    ("kt::App", {"a": 0, "s": ""}, ("0000", "0001", "0008", "0009")),
    ("kt::Mut", {"id": 0, "x": 0, "s": ""}, ("0002", "0003", "000a", "000b")),
])
def test_extensible_headers(kt, type_name, value, idents):
    got = tuple(kt.encode(type_name, value, version=v, little=le)[:2].hex()
                for v, le in ((1, False), (1, True), (2, False), (2, True)))
    assert got == idents


def test_appendable_reader_skips_unknown_trailing_members_and_defaults_missing_ones(kt):
    # a newer writer appended a member (4 more bytes inside the DHEADER): skipped
    longer = h("0009 0000  0f000000  0500 0000 03000000 787900 00 2a000000")
    assert kt.decode("kt::App", longer) == {"a": 5, "s": "xy"}
    # an older writer knew only 'a': 's' takes its default
    shorter = h("0009 0000  02000000  0500")
    assert kt.decode("kt::App", shorter) == {"a": 5, "s": ""}


def test_mutable_reader_takes_members_in_any_order_and_skips_unknown_ones(kt):
    data = h("000b 0000  24000000  02000050 02000000 6b000000  09000020 01000000  01000010 ffff 0000"
             "  000000a0 07000000")
    assert kt.decode("kt::Mut", data) == {"id": 7, "x": -1, "s": "k"}
    # short-form XCDR1 parameter ids are read too
    xcdr1 = h("0003 0000  0040 0400 07000000  0100 0400 ffff0000  027f0000")
    assert kt.decode("kt::Mut", xcdr1) == {"id": 7, "x": -1, "s": ""}
