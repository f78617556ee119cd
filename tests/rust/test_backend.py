"""The rust target on hostile names and text, on the union and array shapes RAPID does not
use, under clippy, and on what it cannot express (RG1703)."""
from __future__ import annotations

import json
import shutil
import struct
import subprocess
import sys
from pathlib import Path

import pytest

from rapidgen.backends import escape
from rapidgen.backends.rust import namer
from tests.rust.conftest import K10, build_programs, cargo, run

TRICKY = r'''
module cdr {
    struct Vec { long type; string<4> self; long srcName; long src_name; };
};
module m {
    const string TXT = "q\"b\\s \u202e bidi */ /* tab\t nl\n e\u00e9 \u706b end\\";
    const long long LOW = -9223372036854775807 - 1;
    const unsigned long long HIGH = 18446744073709551615;
    const float F = 0.1;
    const char C = 'x';
    enum E { self, Self_, RED };
    @bit_bound(8) enum Small { A, B };
    union U switch (long) { case 1: case 3: long a; case 2: string b; default: E c; };
    union V switch (E) { case RED: long r; };
    union W switch (boolean) { case TRUE: long t; case FALSE: short f; };
    union X switch (char) { case 'a': Small s; };
    module m { struct Inner { long x; }; };
    struct S {
        E e; U u; V v; W w; X x; cdr::Vec vec; sequence<U, 2> us; short grid[2][3]; double big[40];
        char c; octet o; string<8> id; sequence<sequence<m::Inner>> nested; Small sm;
    };
    struct Empty { };
    struct HasEmpty { sequence<Empty> es; };
    struct K { @key string<8> id; long value; @key short n; };
};
'''
TXT_VALUE = 'q"b\\s \u202e bidi */ /* tab\t nl\n e\u00e9 \u706b end\\'

# Prints the constants' values and round-trips values the vectors do not hold.
MAIN = r'''
use gen::cdr::{deserialize, serialize, Endianness};
use gen::cdr::{key_bytes, Cdr};
use gen::m::{E, HasEmpty, K, S, U, V, TXT, LOW, HIGH, F, C};

fn main() {
    let hex: String = TXT.bytes().map(|b| format!("{b:02x}")).collect();
    println!("{hex} {LOW} {HIGH} {} {C}", F.to_bits());
    let mut s = S::default();
    s.vec.type_ = 7;
    s.vec.self_ = "abcd".into();
    s.vec.src_name = 1;
    s.vec.src_name_ = 2;
    s.e = E::Self__;
    s.u = U::A(3, 5);
    s.v = V::NoMember(E::Self_);
    s.us = vec![U::C(9, E::Red), U::B("x".into())];
    s.big[39] = -0.0;
    let back: S = deserialize(&serialize(&s, Endianness::Big).unwrap()).unwrap();
    println!("{}", back == s && back.big[39].is_sign_negative());
    s.vec.self_ = "abcde".into();
    println!("{}", serialize(&s, Endianness::Little).is_err());
    s.vec.self_ = "ab".into();
    s.u = U::A(2, 5); // 2 selects `b`, not `a`
    println!("{}", serialize(&s, Endianness::Little).is_err());
    s.u = U::C(1, E::Red); // 1 is a label of `a`: not the default branch
    println!("{}", serialize(&s, Endianness::Little).is_err());
    s.u = U::default();
    s.v = V::NoMember(E::Red); // RED selects `r`
    println!("{}", serialize(&s, Endianness::Little).is_err());
    // 70000 empty structs announced in 8 bytes: over the limit for zero-size elements
    let bytes = [0u8, 1, 0, 0, 0x70, 0x11, 0x01, 0x00];
    println!("{}", deserialize::<HasEmpty>(&bytes).is_err());
    // key members in big-endian CDR from offset 0: "ab" (length 3 with NUL), pad to 2, 7
    let k = K { id: "ab".into(), value: 5, n: 7 };
    let hex: String = key_bytes(&k).unwrap().iter().map(|b| format!("{b:02x}")).collect();
    println!("{hex} {} {}", K::KEYED, S::KEYED);
}
'''


def _generate(tmp_path, idl: str, *args: str) -> subprocess.CompletedProcess:
    (tmp_path / "t.idl").write_text(idl, encoding="utf-8")
    return subprocess.run([sys.executable, "-m", "rapidgen", *args, str(tmp_path / "t.idl")],
                          capture_output=True, text=True, timeout=120)


def _clippy(crate: Path, target, tmp_path) -> subprocess.CompletedProcess | None:
    """clippy -D warnings on a copy of the crate (cargo writes Cargo.lock beside it)."""
    if subprocess.run([cargo(), "clippy", "--version"], capture_output=True, stdin=subprocess.DEVNULL).returncode != 0:
        return None
    copy = tmp_path / "clippy" / crate.name
    shutil.copytree(crate, copy)
    return run([cargo(), "clippy", "--offline", "--all-targets", "--", "-D", "warnings"], copy, target)


def test_hostile_names_and_shapes_compile_clippy_clean_and_round_trip(tmp_path, rust_target):
    res = _generate(tmp_path, TRICKY, "generate", "--lang", "rust", "--package", "tricky", "-o", str(tmp_path / "out"))
    assert res.returncode == 0, res.stderr
    crate = tmp_path / "out" / "rust"
    lib = (crate / "src" / "m.rs").read_text(encoding="utf-8")
    assert "\u202e" not in lib and "pub mod m_;" in lib  # no raw bidi override; no module inception
    if _clippy(crate, rust_target, tmp_path) is None:
        print("clippy is not installed: the clippy check is skipped")
    main = tmp_path / "main.rs"
    main.write_text(MAIN, encoding="utf-8")
    (tmp_path / "h").mkdir()
    bins = build_programs(tmp_path / "h", crate, "tricky", rust_target, {"tricky_main": main})
    out = subprocess.run([str(bins / "tricky_main")], capture_output=True, text=True, timeout=30)
    assert out.returncode == 0, out.stderr
    f_bits = int.from_bytes(struct.pack("<f", 0.1), "little")
    assert out.stdout.split() == [TXT_VALUE.encode().hex(), str(-2**63), str(2**64 - 1), str(f_bits), str(ord("x")),
                                  "true", "true", "true", "true", "true", "true", "00000003616200000007", "true", "false"]
    # the reference encoder's vectors of these types: byte-identical both ways, and fuzzed
    res = _generate(tmp_path, TRICKY, "vectors", "-o", str(tmp_path / "v.json"))
    assert res.returncode == 0, res.stderr
    data = json.loads((tmp_path / "v.json").read_text(encoding="utf-8"))
    lines = "\n".join(f"{v['id']} {v['type']} {v['xcdr1_le']} {v['xcdr1_be']}" for v in data["vectors"])
    got = subprocess.run([str(bins / "vectors")], input=lines, capture_output=True, text=True, timeout=60)
    assert got.returncode == 0 and got.stdout.split()[-2:] == ["ok", str(data["count"])], got.stdout[-3000:]
    got = subprocess.run([str(bins / "fuzz"), "100"], input=lines, capture_output=True, text=True, timeout=120)
    assert got.returncode == 0, got.stdout[-3000:] + got.stderr[-3000:]


def test_generated_k10_crate_is_clippy_clean(tmp_path, rust_target):
    if _clippy(K10, rust_target, tmp_path) is None:
        pytest.skip("clippy is not installed (rustup component add clippy, or Debian's rust-clippy)")


def test_unsupported_constructs_are_located_errors_and_nothing_is_written(tmp_path):
    idl = ("module m {\n"
           "  bitmask F { A, B };\n"
           "  struct S {\n"
           "    wstring w;\n"
           "    map<long, long> mp;\n"
           "    @optional long o;\n"
           "    long fine;\n"
           "  };\n"
           "  @mutable struct T { long x; };\n"
           "};\n")
    res = _generate(tmp_path, idl, "generate", "--lang", "rust", "-o", str(tmp_path / "out"))
    assert res.returncode == 1, res.stderr
    lines = [ln for ln in res.stderr.splitlines() if "error[RG1703]" in ln]
    assert [ln.split(":")[1] for ln in lines] == ["2", "4", "5", "6", "9"], res.stderr
    assert "Traceback" not in res.stderr
    assert not (tmp_path / "out" / "rust").exists()


def test_rust_escapes_and_names():
    for text in ["", "plain", 'q"\\', "\x00\x01\n\x7f", "é火🚀", "\u202e", "{}"]:
        lit = escape.rust_str(text)
        assert lit.isascii() and "\n" not in lit and lit[0] == lit[-1] == '"'
        body = lit[1:-1]
        # the literal's escapes decode (as Rust does) to exactly the text
        out = ""
        i = 0
        while i < len(body):
            if body[i] == "\\" and body[i + 1] in '"\\':
                out += body[i + 1]
                i += 2
            elif body[i] == "\\":
                end = body.index("}", i)
                out += chr(int(body[i + 3:end], 16))
                i = end + 1
            else:
                assert body[i] != '"'
                out += body[i]
                i += 1
        assert out == text
    for text in ["two\nlines", "\x1b[31m", "\u202e rtl", "cr\r"]:
        c = escape.rust_comment(text)
        assert c.isprintable() and "\n" not in c and "\r" not in c
    assert escape.crate_name("K10 Red!") == "k10_red" and escape.crate_name("9x") == "rapid_9x"
    assert escape.crate_name("test") == "test_rs" and escape.crate_name("") == "rapid_types"
    assert (namer.snake("srcName"), namer.camel("ACK_COMPLETED"), namer.camel("GPS"), namer.upper("maxItems")) == \
        ("src_name", "AckCompleted", "Gps", "MAX_ITEMS")
    scope = namer.Scope("t")
    assert [scope.claim(namer.snake(n), n) for n in ["srcName", "src_name", "type", "type_"]] == \
        ["src_name", "src_name_", "type_", "type__"]
