"""The largest key encoding (rapidgen/model/wire.py) decides between the key bytes and their
MD5 in the RTPS key hash: XCDR1 big-endian from offset 0, alignment counted where it falls
(not at its worst per member). The C++ and Rust targets print the same figure."""
from __future__ import annotations

import re
import subprocess
import sys

IDL = """
module k {
    struct Two64 { @key long long a; @key long long b; long v; };
    struct OctetThen64 { @key octet o; @key long long a; };
    struct Over { @key long long a; @key long long b; @key octet c; };
    struct Str { @key long id; @key string<8> name; };
    struct Free { @key string name; };
    struct Inner { long long x; };
    struct Nested { @key Inner i; @key short s; };
};
"""
EXPECTED = {"Two64": 16, "OctetThen64": 16, "Over": 17, "Str": 17, "Nested": 10}


def _generate(tmp_path, lang: str) -> str:
    (tmp_path / "k.idl").write_text(IDL, encoding="utf-8")
    out = tmp_path / lang
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(tmp_path / "k.idl"), "--lang", lang,
                          "-o", str(out)], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    return "\n".join(p.read_text(encoding="utf-8") for p in sorted(out.rglob("*")) if p.suffix in (".hpp", ".rs"))


def test_cpp_and_rust_agree_on_each_key_size(tmp_path):
    cpp = _generate(tmp_path, "cpp")
    rust = _generate(tmp_path, "rust")
    cpp_sizes = dict(re.findall(r"struct Traits<::k::(\w+)>.*?key_max = (\d+)u;", cpp, re.S))
    # (an impl without a key leaves KEY_MAX_SIZE to the trait's 0: do not run into the next impl)
    rust_sizes = dict(re.findall(r"impl crate::cdr::Cdr for (\w+) \{(?:(?!\nimpl ).)*?KEY_MAX_SIZE: usize = (\d+);",
                                 rust, re.S))
    for name, size in EXPECTED.items():
        assert int(cpp_sizes[name]) == size, (name, cpp_sizes)
        assert int(rust_sizes[name]) == size, (name, rust_sizes)
    # an unbounded key is past the 16 bytes in both
    assert int(cpp_sizes["Free"]) > 16 and int(rust_sizes["Free"]) > 16
