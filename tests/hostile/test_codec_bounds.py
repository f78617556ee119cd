"""The reference CDR decoder's memory stays in proportion to its input (issue 8, item 11):
a few bytes cannot make 10^8 default elements or nested sequences of empty structs. Each
hostile case runs `Codec.decode` in a bounded child and must end in a clean CdrError."""
from __future__ import annotations

import struct

from tests.hostile.limits import run_python

MEM, CPU = 1024, 20  # MiB, CPU seconds

IDL = """module m {
  @mutable struct Big { long id; long x[10000][10000]; };
  @final struct Empty { };
  struct Nest { sequence<sequence<Empty> > s; };
  @appendable struct A { long a; long b; long c; };
  struct Items { sequence<A> items; };
};
"""

CHILD = """
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.cdr import CdrError, Codec
from rapidgen.vectors import load_model
sink = DiagnosticSink()
model = load_model(["t.idl"], [], sink)
assert model is not None, [str(d) for d in sink.diagnostics]
try:
    value = Codec(model).decode({type!r}, {data!r})
    print("decoded", repr(value)[:200])
except CdrError as exc:
    print("CdrError:", exc)
"""


def decode_in_child(tmp_path, type_name: str, data: bytes) -> str:
    (tmp_path / "t.idl").write_text(IDL)
    res = run_python(CHILD.format(type=type_name, data=data), cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    assert not res.killed, f"killed by signal {-res.code}"
    assert res.code == 0 and "Traceback" not in res.err, res.err[-2000:]
    return res.out.strip()


def test_absent_mutable_member_cannot_default_to_a_huge_array(tmp_path):
    # PL_CDR2_LE, DHEADER 0: every member absent; 'x' would default to 10^8 longs
    out = decode_in_child(tmp_path, "m::Big", bytes([0, 0x0B, 0, 0]) + struct.pack("<I", 0))
    assert out.startswith("CdrError: the default of absent member 'x' would make the value hold more than")


def test_nested_sequences_of_empty_structs_are_bounded_by_the_input(tmp_path):
    # XCDR1: 2000 inner sequences, each claiming 65536 empty structs (9 GB before the fix)
    n = 2000
    data = bytes([0, 1, 0, 0]) + struct.pack("<I", n) + struct.pack("<I", 65536) * n
    out = decode_in_child(tmp_path, "m::Nest", data)
    assert out.startswith("CdrError: sequence of 65536 elements would make the value hold more than")


def test_appendable_elements_from_an_older_writer_decode(tmp_path):
    # CDR2_LE: three A's, each a DHEADER of 4 and only 'a' (the writer knew no 'b', 'c').
    # Refused before the fix: min_size counted every member of A, 16 bytes per element.
    elements = (struct.pack("<I", 4) + struct.pack("<i", 7)) * 3
    body = struct.pack("<I", 3) + elements
    data = bytes([0, 0x07, 0, 0]) + struct.pack("<I", len(body)) + body
    out = decode_in_child(tmp_path, "m::Items", data)
    assert out == "decoded " + repr({"items": [{"a": 7, "b": 0, "c": 0}] * 3})
