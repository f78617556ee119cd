"""Mutation fuzzing of the IDL front end: broken input gives diagnostics, never a crash.

Valid samples (RTI valuetype dialect, IDL 4 with annotations, a preprocessor-heavy
pair of files, a Cyclone-style file) are mutated token-wise and byte-wise (delete,
duplicate, swap, insert random characters or bytes including NUL and non-UTF-8,
truncate), written to a temporary folder and run through `rapidgen ir` in-process.

Whatever comes out, the run must end with exit 0 or 1, never print a traceback or an
internal error, and a failed run must name a file, line and column with an error code.

More examples: RAPIDGEN_FUZZ_EXAMPLES=5000 pytest tests/fuzz
"""
from __future__ import annotations

import contextlib
import os
import re
import tempfile

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.helpers import rapidgen

# -- valid samples: {file name: text}; the first file is the one compiled ----------------------

RTI_DIALECT = {
    "Message.idl": """\
// RAPID-style valuetypes with RTI's //@key comments.
module rapid {
  typedef string<64> String64;
  const long MAX_PARAMS = 64;
  enum ParameterType { RAPID_STRING, RAPID_INT, RAPID_BOOL, RAPID_DOUBLE };
  valuetype Header {
    public String64 srcName; //@key
    public String64 assetName; //@key
    public long long timeStamp;
    public long serial;
  };
  valuetype Message : Header {
    public sequence<ParameterType, MAX_PARAMS> types;
    public double values[3];
    public string<128> text;
  };
};
""",
}

IDL4 = {
    "demo.idl": """\
module demo {
  @bit_bound(16) bitmask Flags { @position(0) READY, BUSY, FAULT };
  bitset Packed { bitfield<3> mode; bitfield<5> level; bitfield<1, boolean> on; };
  enum Kind { @value(1) K_INT, K_TEXT, K_RAW };
  @final union Value switch (Kind) {
    case K_INT: long i;
    case K_TEXT: string<32> s;
    default: octet raw;
  };
  @appendable struct Sample {
    @key @id(1) uint32 id;
    @optional map<string<16>, double, 8> params;
    Value v;
    @default(3) int16 count;
    @range(min = 0, max = 10) float ratio;
    Flags flags;
    Packed packed;
  };
  @mutable struct Derived : Sample {
    @external sequence<Sample> history;
    wchar w;
    const_check c;
  };
  typedef long const_check;
};
""",
}

PREPROCESSOR = {
    "main.idl": """\
#ifndef MAIN_IDL
#define MAIN_IDL
#include "common.idl"
#define LEN 8
/* #include "not-read.idl" */
#if defined(LEN) && LEN > 4 && !defined(SMALL)
module m {
  struct Big {
    string<LEN> s;
    common::Id id;
    common::Id ids[LEN / 2];
  };
#pragma keylist Big id
};
#elif LEN > 2
module m { struct Small { long s; }; };
#else
#error "LEN is too small"
#endif
#endif // MAIN_IDL
""",
    "common.idl": """\
#ifndef COMMON_IDL
#define COMMON_IDL
module common {
  typedef unsigned long Id;
  const Id FIRST = 0x10;
};
#endif
""",
}

CYCLONE = {
    "cyclone.idl": """\
module c {
  const long N = (1 << 4) + 0x10 % 7 - 010;
  const string<8> NAME = "abc" "def";
  const char SEP = '\\t';
  const double SCALE = 2.5e-3 * N;
  typedef sequence<long, N> Longs;
  struct Point { long x; long y; };
  struct Path {
    Longs ids;
    Point pts[N][2];
    sequence<Path> sub;
    boolean closed;
  };
#pragma keylist Path ids
  union U switch (char) { case 'a': case 'b': long ab; case 'c': Point p; };
};
""",
}

SAMPLES = [RTI_DIALECT, IDL4, PREPROCESSOR, CYCLONE]

_TOKEN = re.compile(rb"\s+|[A-Za-z_][A-Za-z0-9_]*|0[xX][0-9a-fA-F]+|\d+(?:\.\d*)?(?:[eE][-+]?\d+)?|"
                    rb'"(?:[^"\\\n]|\\.)*"|\'(?:[^\'\\\n]|\\.)*\'|//[^\n]*|/\*|\*/|::|<<|>>|.', re.S)

# Characters and byte strings that tend to reach unusual paths.
_SPECIAL = [b"\0", b"\xff", b"\xc3", b"\xe2\x82", b"$", b'"', b"'", b"/*", b"*/", b"//", b"#", b"#if",
            b"#endif", b"#include", b"{", b"}", b"<", b">", b"@", b"::", b";", b"\\", b"\n", b"\r",
            b"\t", b"\x1b", b"\xef\xbb\xbf",
            b"struct", b"module", b"valuetype", b"union", b"case", b"default", b"sequence", b"-",
            b"0x", b"99999999999999999999999", b"1e999", b"L'", b"@key", b"//@key", b"#pragma keylist",
            b"0", b"-1", b"65", b"18446744073709551616", b"0.5", b"TRUE", b"'x'", b'"s"', b">>", b"<<"]


def _tokens(data: bytes) -> list[bytes]:
    return _TOKEN.findall(data)


@st.composite
def mutations(draw, data: bytes) -> bytes:
    toks = _tokens(data)
    for _ in range(draw(st.integers(1, 3))):
        kind = draw(st.sampled_from(["delete", "duplicate", "swap", "insert", "insert_bytes", "truncate",
                                     "replace", "reuse"]))
        if not toks:
            toks = [b""]
        i = draw(st.integers(0, len(toks) - 1))
        if kind == "delete":
            del toks[i]
        elif kind == "duplicate":
            toks.insert(i, toks[i])
        elif kind == "swap":
            j = draw(st.integers(0, len(toks) - 1))
            toks[i], toks[j] = toks[j], toks[i]
        elif kind == "insert":
            toks.insert(i, draw(st.sampled_from(_SPECIAL) | st.text(max_size=4).map(
                lambda s: s.encode("utf-8", "surrogatepass"))))
        elif kind == "insert_bytes":
            toks.insert(i, draw(st.binary(min_size=1, max_size=4)))
        elif kind == "replace":
            toks[i] = draw(st.sampled_from(_SPECIAL))
        elif kind == "reuse":  # another token of the same text: wrong names, duplicates, bad types
            toks[i] = draw(st.sampled_from(toks))
        else:  # truncate, anywhere (also inside a token)
            whole = b"".join(toks)
            toks = [whole[:draw(st.integers(0, len(whole)))]]
    return b"".join(toks)


_WORD = re.compile(rb"[A-Za-z_][A-Za-z0-9_]*")
_NUMBER = re.compile(rb"0[xX][0-9a-fA-F]+|\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")
_NUMBERS = [b"0", b"1", b"2", b"-1", b"7", b"8", b"63", b"64", b"65", b"255", b"256", b"32768", b"65536",
            b"0x7fffffff", b"0xffffffffffffffff", b"18446744073709551616", b"1.5", b"1e400", b"010", b"(1/0)"]


@st.composite
def semantic_mutations(draw, data: bytes) -> bytes:
    """Keep the syntax, change the meaning: swap names for other names, numbers for edge values."""
    toks = _tokens(data)
    words = sorted({t for t in toks if _WORD.fullmatch(t)})
    spots = [i for i, t in enumerate(toks) if _WORD.fullmatch(t) or _NUMBER.fullmatch(t)]
    for _ in range(draw(st.integers(1, 4))):
        i = draw(st.sampled_from(spots))
        pool = _NUMBERS if _NUMBER.fullmatch(toks[i]) else words
        toks[i] = draw(st.sampled_from(pool))
    return b"".join(toks)


@st.composite
def mutated_samples(draw) -> tuple[dict[str, bytes], str]:
    sample = draw(st.sampled_from(SAMPLES))
    files = {name: text.encode("utf-8") for name, text in sample.items()}
    target = draw(st.sampled_from(sorted(files)))
    mutate = draw(st.sampled_from([mutations, mutations, semantic_mutations]))
    files[target] = draw(mutate(files[target]))
    return files, next(iter(sample))


@contextlib.contextmanager
def _inside(folder: str):
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(cwd)


def check_front_end(files: dict[str, bytes], main: str) -> None:
    with tempfile.TemporaryDirectory() as tmp, _inside(tmp):
        for name, data in files.items():
            with open(name, "wb") as fh:
                fh.write(data)
        res = rapidgen("ir", "--no-loc", main)
    assert "Traceback" not in res.err, res.err
    assert "internal error" not in res.err, res.err
    assert res.code in (0, 1), f"exit {res.code}\n{res.err}"
    if res.code == 1:
        names = "|".join(re.escape(n) for n in files)
        assert re.search(rf"^(?:{names}):\d+:\d+: error\[RG\d{{4}}\]", res.err, re.M), res.err
    else:
        assert res.out.startswith("{"), res.out[:200]


_EXAMPLES = int(os.environ.get("RAPIDGEN_FUZZ_EXAMPLES", "300"))


@pytest.mark.parametrize("sample", SAMPLES, ids=["rti", "idl4", "preprocessor", "cyclone"])
def test_samples_are_valid(sample):
    """The unmutated samples compile cleanly, so the mutations start from good input."""
    with tempfile.TemporaryDirectory() as tmp, _inside(tmp):
        for name, text in sample.items():
            with open(name, "w", encoding="utf-8") as fh:
                fh.write(text)
        res = rapidgen("ir", "--no-loc", next(iter(sample)))
    assert (res.code, res.err) == (0, ""), res.err


@settings(max_examples=_EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow],
          database=None)
@given(mutated_samples())
def test_mutated_input_never_crashes(case):
    files, main = case
    check_front_end(files, main)
