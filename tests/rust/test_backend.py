"""The rust target on hostile names and text, on the union and array shapes RAPID does not
use (arrays over 32 also under serde), under clippy with every feature, through serde_json,
and on what it cannot express (RG1703)."""
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
from tests.rust.conftest import (HERE, K10, PEER_LOCK, VECTORS, build_programs, build_serde_programs, cargo, run,
                                 skip_unless_registry_toolchain, vector_lines)

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
    struct K8 { @key long long a; @key octet o; @key long long b; };
    typedef double Row40[40];
    union BU switch (short) { case 1: Row40 row; case 2: long x; };
    struct Big { sequence<Row40, 3> rows; Row40 pair[2]; short small[33][2]; BU bu; };
};
'''
TXT_VALUE = 'q"b\\s \u202e bidi */ /* tab\t nl\n e\u00e9 \u706b end\\'

# Prints the constants' values and round-trips values the vectors do not hold.
MAIN = r'''
use gen::cdr::{deserialize, serialize, Endianness};
use gen::cdr::{key_bytes, transcode_key, Cdr};
use gen::m::{E, HasEmpty, K, K8, S, U, V, TXT, LOW, HIGH, F, C};

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
    // the same key in little-endian (a dispose's serialized key); its largest encoding
    let le = transcode_key::<K>(&key_bytes(&k).unwrap(), Endianness::Big, Endianness::Little).unwrap();
    let hex: String = le.iter().map(|b| format!("{b:02x}")).collect();
    println!("{hex} {} {} {}", K::KEY_MAX_SIZE, K8::KEY_MAX_SIZE, S::KEY_MAX_SIZE);
    // a key one byte short, or with bytes after it, is refused
    println!("{} {}", transcode_key::<K>(&le[..9], Endianness::Little, Endianness::Big).is_err(),
             transcode_key::<K>(&[le.clone(), vec![0; 4]].concat(), Endianness::Little, Endianness::Big).is_err());
}
'''


# The serde build of the hostile crate: names as the IDL spells them, arrays over 32 at
# every depth (in sequences, arrays of arrays, a union branch) as JSON lists, refused at
# another length.
TRICKY_JSON = r"""
use gen::m::{Big, Bu, E, S, U};

fn main() {
    let mut s = S::default();
    s.vec.type_ = 7;
    s.vec.self_ = "abcd".into();
    s.vec.src_name = 1;
    s.vec.src_name_ = 2;
    s.e = E::Self__;
    s.u = U::A(3, 5);
    s.big[39] = -2.5;
    let text = serde_json::to_string(&s).unwrap();
    println!("{}", serde_json::from_str::<S>(&text).unwrap() == s);
    println!("{text}");
    let mut big = Big::default();
    big.rows = vec![[1.5; 40], [2.5; 40]];
    big.pair[1][39] = 3.0;
    big.small[32] = [4, 5];
    big.bu = Bu::Row([6.0; 40]);
    let text = serde_json::to_string(&big).unwrap();
    println!("{}", serde_json::from_str::<Big>(&text).unwrap() == big);
    println!("{text}");
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["pair"][1].as_array_mut().unwrap().pop();
    println!("{}", serde_json::from_value::<Big>(v.clone()).is_err());
    v["pair"][1].as_array_mut().unwrap().extend([1.0.into(), 2.0.into()]);
    println!("{}", serde_json::from_value::<Big>(v).is_err());
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["small"].as_array_mut().unwrap().push(serde_json::json!([1, 2]));
    println!("{}", serde_json::from_value::<Big>(v).is_err());
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["rows"][0].as_array_mut().unwrap().pop();
    println!("{}", serde_json::from_value::<Big>(v).is_err());
}
"""


def _generate(tmp_path, idl: str, *args: str) -> subprocess.CompletedProcess:
    (tmp_path / "t.idl").write_text(idl, encoding="utf-8")
    return subprocess.run([sys.executable, "-m", "rapidgen", *args, str(tmp_path / "t.idl")],
                          capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def tricky(tmp_path_factory) -> Path:
    """The crate generated from TRICKY (package `tricky`)."""
    tmp = tmp_path_factory.mktemp("tricky")
    res = _generate(tmp, TRICKY, "generate", "--lang", "rust", "--package", "tricky", "-o", str(tmp / "out"))
    assert res.returncode == 0, res.stderr
    return tmp / "out" / "rust"


def _has_clippy() -> bool:
    return subprocess.run([cargo(), "clippy", "--version"], capture_output=True, stdin=subprocess.DEVNULL).returncode == 0


def _clippy(crate: Path, target, tmp_path, *args: str) -> None:
    """clippy -D warnings on a copy of the crate, its lock started from the peer's (a crate
    built on its own resolves its optional dependencies too, whatever the features)."""
    copy = tmp_path / "clippy" / crate.name
    shutil.copytree(crate, copy)
    shutil.copyfile(PEER_LOCK, copy / "Cargo.lock")
    run([cargo(), "clippy", *args, "--all-targets", "--", "-D", "warnings"], copy, target)


def test_hostile_names_and_shapes_compile_and_round_trip(tmp_path, rust_target, tricky):
    crate = tricky
    lib = (crate / "src" / "m.rs").read_text(encoding="utf-8")
    assert "\u202e" not in lib and "pub mod m_;" in lib  # no raw bidi override; no module inception
    # serde's derive stops at 32 elements: every member holding a longer array has the helper
    assert lib.count('serde(with = "crate::serde_arrays::') == 5 and (crate / "src" / "serde_arrays.rs").exists()
    assert 'with = "crate::serde_arrays::Seq::<crate::serde_arrays::Arr::<crate::serde_arrays::Plain>>"' in lib
    assert 'with = "crate::serde_arrays::Arr::<crate::serde_arrays::Arr::<crate::serde_arrays::Plain>>"' in lib
    main = tmp_path / "main.rs"
    main.write_text(MAIN, encoding="utf-8")
    (tmp_path / "h").mkdir()
    bins = build_programs(tmp_path / "h", crate, "tricky", rust_target, {"tricky_main": main})
    out = subprocess.run([str(bins / "tricky_main")], capture_output=True, text=True, timeout=30)
    assert out.returncode == 0, out.stderr
    f_bits = int.from_bytes(struct.pack("<f", 0.1), "little")
    assert out.stdout.split() == [TXT_VALUE.encode().hex(), str(-2**63), str(2**64 - 1), str(f_bits), str(ord("x")),
                                  "true", "true", "true", "true", "true", "true", "00000003616200000007", "true", "false",
                                  # string<8> at 0 (4 + 9), short aligned to 14: 16; 8 + 1, aligned to 16, + 8
                                  "03000000616200000700", "16", "24", "0", "true", "true"]
    # the reference encoder's vectors of these types: byte-identical both ways, and fuzzed
    res = _generate(tmp_path, TRICKY, "vectors", "-o", str(tmp_path / "v.json"))
    assert res.returncode == 0, res.stderr
    data = json.loads((tmp_path / "v.json").read_text(encoding="utf-8"))
    lines = "\n".join(f"{v['id']} {v['type']} {v['xcdr1_le']} {v['xcdr1_be']}" for v in data["vectors"])
    got = subprocess.run([str(bins / "vectors")], input=lines, capture_output=True, text=True, timeout=60)
    assert got.returncode == 0 and got.stdout.split()[-2:] == ["ok", str(data["count"])], got.stdout[-3000:]
    got = subprocess.run([str(bins / "fuzz"), "100"], input=lines, capture_output=True, text=True, timeout=120)
    assert got.returncode == 0, got.stdout[-3000:] + got.stderr[-3000:]


@pytest.mark.parametrize("features", ["default", "all"])
@pytest.mark.parametrize("which", ["k10", "tricky"])
def test_generated_crates_are_clippy_clean_with_every_feature(which, features, tmp_path, rust_target, tricky):
    if not _has_clippy():
        pytest.skip("clippy is not installed (rustup component add clippy, or Debian's rust-clippy)")
    skip_unless_registry_toolchain()  # the lock the copy starts from; `dds` builds RustDDS
    _clippy(K10 if which == "k10" else tricky, rust_target, tmp_path, *(["--all-features"] if features == "all" else []))


def _f32(x: float) -> float | None:
    try:
        return struct.unpack("<f", struct.pack("<f", x))[0]
    except OverflowError:
        return None


def _same(got: object, want: object) -> bool:
    """serde_json's text of a value against the vectors' value form (docs/cdr-and-vectors.md):
    the same names and values; a float32 written shortest; a union as {member: value}."""
    if isinstance(want, dict) and "discriminator" in want and set(want) <= {"discriminator", "value"}:
        if not (isinstance(got, dict) and len(got) == 1):
            return False
        (member, value), = got.items()
        return _same(value, want["value"]) if "value" in want else member == "NoMember"
    if isinstance(want, dict):
        return isinstance(got, dict) and got.keys() == want.keys() and all(_same(got[k], want[k]) for k in want)
    if isinstance(want, list):
        return isinstance(got, list) and len(got) == len(want) and all(map(_same, got, want))
    if isinstance(want, float):
        return isinstance(got, float) and (got == want or _f32(got) == _f32(want) is not None)
    return type(got) is type(want) and got == want


def test_serde_json_round_trips_every_vector_with_the_idl_names(tmp_path, rust_target):
    (tmp_path / "h").mkdir()
    bins = build_serde_programs(tmp_path / "h", K10, "rapid_k10red", rust_target,
                                {"json": HERE / "src" / "json.rs"})
    got = subprocess.run([str(bins / "json")], input="\n".join(vector_lines()), capture_output=True, text=True,
                         timeout=120)
    vectors = {v["id"]: v for v in json.loads(VECTORS.read_text(encoding="utf-8"))["vectors"]}
    assert got.returncode == 0 and got.stdout.split()[-2:] == ["ok", str(len(vectors))], got.stdout[-3000:]
    texts = dict(line.split(" ", 2)[1:] for line in got.stdout.splitlines() if line.startswith("json "))
    assert texts.keys() == vectors.keys()
    wrong = [i for i, text in texts.items() if not _same(json.loads(text), vectors[i]["value"])]
    assert not wrong, f"{len(wrong)} differ from the value form, first {wrong[0]}: {texts[wrong[0]]}"
    assert '"srcName":' in texts["rapid::Ack/max"] and '"ACK_COMPLETED"' in "".join(texts.values())


def test_serde_of_hostile_names_and_long_arrays(tmp_path, rust_target, tricky):
    main = tmp_path / "tricky_json.rs"
    main.write_text(TRICKY_JSON, encoding="utf-8")
    (tmp_path / "h").mkdir()
    bins = build_serde_programs(tmp_path / "h", tricky, "tricky", rust_target, {"tricky_json": main})
    out = subprocess.run([str(bins / "tricky_json")], capture_output=True, text=True, timeout=30)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0] == lines[2] == "true" and lines[4:] == ["true"] * 4, out.stdout
    s, big = json.loads(lines[1]), json.loads(lines[3])
    assert s["vec"] == {"type": 7, "self": "abcd", "srcName": 1, "src_name": 2}
    assert s["e"] == "Self_" and s["u"] == {"a": [3, 5]} and s["grid"] == [[0, 0, 0], [0, 0, 0]]
    assert len(s["big"]) == 40 and s["big"][39] == -2.5
    assert big["rows"] == [[1.5] * 40, [2.5] * 40] and big["bu"] == {"row": [6.0] * 40}
    assert big["pair"] == [[0.0] * 40, [0.0] * 39 + [3.0]]
    assert len(big["small"]) == 33 and big["small"][32] == [4, 5]


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
