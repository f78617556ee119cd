"""The codec's bulk paths (sequences and arrays of every primitive, booleans checked byte by
byte, enums, unions holding arrays, an empty sequence last, odd alignments before each run)
against the reference encoder: every vector decodes from both byte orders and re-encodes
byte-identically with one exact allocation, and the fuzz loop finds no panic nor
over-allocation. The golden RAPID vectors only exercise f32, f64, i32 and octet runs."""
from __future__ import annotations

import json
import subprocess

from tests.rust.conftest import build_programs
from tests.rust.test_backend import _generate

BULK = """
module b {
  enum Color { RED, GREEN, BLUE };
  struct Seqs {
    octet o0; sequence<boolean> bo; octet o1; sequence<octet> oc; sequence<char> ch;
    octet o2; sequence<int8> i8s; octet o3; sequence<uint8> u8s;
    octet o4; sequence<int16> i16s; octet o5; sequence<uint16, 5> u16s;
    octet o6; sequence<long> i32s; octet o7; sequence<unsigned long> u32s;
    octet o8; sequence<long long> i64s; octet o9; sequence<unsigned long long> u64s;
    octet o10; sequence<float> f32s; octet o11; sequence<double, 7> f64s;
    sequence<Color> colors; octet o12; sequence<double> tail;
  };
  struct Arrs {
    octet o0; boolean bo[3]; octet o1; octet oc[5]; char ch[2];
    int8 i8a[3]; uint8 u8a[2]; octet o4; short i16a[3]; unsigned short u16a[2][3];
    octet o6; long i32a[2]; octet o7; unsigned long u32a[3];
    octet o8; long long i64a[2]; octet o9; unsigned long long u64a[1];
    octet o10; float f32a[3][2]; octet o11; double f64a[2][2][2];
    boolean bo2[2][2]; sequence<short> ss[2];
  };
  union BU switch (long) { case 1: double d[3]; case 2: sequence<boolean> bs; case 3: sequence<long long> ls; default: octet o; };
  struct Tail { octet a; sequence<double> empty; };
  struct Wrap { octet a; BU u; sequence<BU> us; Arrs arr[2]; sequence<Seqs, 2> ss; };
};
"""


def test_bulk_paths_match_the_reference_encoder_and_survive_fuzzing(tmp_path, rust_target):
    res = _generate(tmp_path, BULK, "generate", "--lang", "rust", "--package", "bulk", "-o", str(tmp_path / "out"))
    assert res.returncode == 0, res.stderr
    res = _generate(tmp_path, BULK, "vectors", "-o", str(tmp_path / "v.json"))
    assert res.returncode == 0, res.stderr
    data = json.loads((tmp_path / "v.json").read_text(encoding="utf-8"))
    assert {v["type"] for v in data["vectors"]} >= {"b::Seqs", "b::Arrs", "b::BU", "b::Tail", "b::Wrap"}
    lines = "\n".join(f"{v['id']} {v['type']} {v['xcdr1_le']} {v['xcdr1_be']}" for v in data["vectors"])
    (tmp_path / "h").mkdir()
    bins = build_programs(tmp_path / "h", tmp_path / "out" / "rust", "bulk", rust_target)
    got = subprocess.run([str(bins / "vectors")], input=lines, capture_output=True, text=True, timeout=60)
    assert got.returncode == 0 and got.stdout.split()[-2:] == ["ok", str(data["count"])], got.stdout[-3000:]
    got = subprocess.run([str(bins / "fuzz"), "200"], input=lines, capture_output=True, text=True, timeout=300)
    assert got.returncode == 0, got.stdout[-3000:] + got.stderr[-3000:]
