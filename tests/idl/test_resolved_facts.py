"""Type-level facts the front end resolves once and the IR stores (`rapidgen ir` shows
them): member ids, enum defaults, union defaults."""
from __future__ import annotations

from rapidgen.idl.facts import name_hash
from tests.helpers import errors_of, ir_of


def _decl(data: dict, name: str) -> dict:
    return next(d for d in data["declarations"] if d["name"] == name)


def test_member_ids_per_declaring_type(tmp_path):
    data = ir_of(tmp_path, """module m {
      @mutable struct A { long a; @id(10) long b; long c; @hashid long d; long e; @hashid("x") long f; };
      @mutable @autoid(HASH) struct B : A { long g; @id(3) long h; long i; };
      @mutable struct C : B { long j; };
      union U switch (long) { case 1: long p; case 2: @id(9) long q; default: long r; };
      @autoid(HASH) union V switch (long) { case 1: long s; };
    };""")
    ids = {m["name"]: m["member_id"] for n in ("m::A", "m::B", "m::C") for m in _decl(data, n)["members"]}
    d = name_hash("d")
    assert ids == {"a": 0, "b": 10, "c": 11, "d": d, "e": d + 1, "f": name_hash("x"),
                   "g": name_hash("g"), "h": 3, "i": name_hash("i"), "j": name_hash("i") + 1}
    assert _decl(data, "m::B")["autoid"] == "HASH" and "autoid" not in _decl(data, "m::C")
    assert [c["member_id"] for c in _decl(data, "m::U")["cases"]] == [0, 9, 10]
    assert [c["member_id"] for c in _decl(data, "m::V")["cases"]] == [name_hash("s")]


def test_enum_and_union_defaults(tmp_path):
    data = ir_of(tmp_path, """module m {
      enum E { A, @default_literal B, C };
      enum F { X, Y };
      typedef E TE;
      union ByE switch (TE) { case A: long a; case B: long b; };
      union ByF switch (F) { case Y: long y; default: long other; };
      union ByBool switch (boolean) { case TRUE: long t; };
      union ByChar switch (char) { case 'a': long a; case '\\0': long nul; };
      union Zero switch (long) { case 1: long one; case 0: long zero; default: long other; };
    };""")
    assert _decl(data, "m::E")["default"] == "B" and _decl(data, "m::F")["default"] == "X"
    by_e = _decl(data, "m::ByE")
    assert by_e["default_discriminator"] == {"enum": "m::E", "name": "B", "value": 1}
    assert by_e["default_case"] == 1
    by_f = _decl(data, "m::ByF")
    assert by_f["default_discriminator"]["name"] == "X" and by_f["default_case"] == 1  # the default: case
    assert (_decl(data, "m::ByBool")["default_discriminator"], _decl(data, "m::ByBool")["default_case"]) == (False, None)
    assert (_decl(data, "m::ByChar")["default_discriminator"], _decl(data, "m::ByChar")["default_case"]) == ("\0", 1)
    assert _decl(data, "m::Zero")["default_case"] == 1  # the labelled case wins over default:


def test_a_hashid_without_utf8_bytes_is_a_located_error(tmp_path):
    """A lone surrogate has no UTF-8 form to hash: an input error, found by resolution."""
    res = errors_of(tmp_path, 'struct S { @hashid("\\ud800") long a; };\n')
    assert res.code == 1, res.err
    assert "t.idl:1:" in res.err and "RG0502" in res.err and "lone surrogate" in res.err
    assert "Traceback" not in res.err
