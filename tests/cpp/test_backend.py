"""The cpp target on hostile names and text, and on what it cannot express (RG1702)."""
from __future__ import annotations

import subprocess
import sys

from rapidgen.backends import escape

TRICKY = r'''
module std {
    struct encode { long class; string<4> errno; long linux; };
};
module m {
    const string TXT = "q\"b\\s??/ tab\t nl\n e\u00e9 */ /* end\\";
    const long long LOW = -9223372036854775807 - 1;
    enum E { and, B };
    union U switch (long) { case 1: case 3: long case_of; case 2: string m_v; default: E or; };
    struct S { E e; U u; std::encode x; sequence<U, 2> us; short grid[2][3]; };
    struct K { @key string<8> id; long value; };
};
'''
TXT_VALUE = 'q"b\\s??/ tab\t nl\n e\u00e9 */ /* end\\'

MAIN = r'''
#include <cstdio>
#include <tricky/topics.hpp>
int main() {
    for (unsigned char c : m::TXT) std::printf("%02x", c);
    std::printf(" %lld", static_cast<long long>(m::LOW));
    m::S s;
    s.x.class_ = 7;
    s.x.errno_ = "abcd";
    s.u.or_(m::E::and_);
    s.us.resize(2);
    s.us[1].case_of_(5);
    s.grid[1][2] = -3;
    m::S back = rapidgen::cdr::deserialize<m::S>(rapidgen::cdr::serialize(s, rapidgen::cdr::Endianness::big));
    std::printf(" %d %d", back == s ? 1 : 0, back.u.or_() == m::E::and_ && back.us[1].case_of_() == 5 && back.us[1]._d() == 1 ? 1 : 0);
    s.x.errno_ = "abcde";
    try { rapidgen::cdr::serialize(s); std::printf(" nobound"); } catch (const rapidgen::cdr::EncodeError&) { std::printf(" bound"); }
    m::KPubSubType kt;
    std::printf(" %s\n", kt.getName());
    return 0;
}
'''


def _generate(tmp_path, idl: str) -> subprocess.CompletedProcess:
    (tmp_path / "t.idl").write_text(idl, encoding="utf-8")
    return subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(tmp_path / "t.idl"), "--lang", "cpp",
                           "--package", "tricky", "-o", str(tmp_path / "out")], capture_output=True, text=True,
                          timeout=120)


def test_hostile_names_and_text_compile_warning_free_and_keep_their_values(tmp_path):
    res = _generate(tmp_path, TRICKY)
    assert res.returncode == 0, res.stderr
    pkg = tmp_path / "out" / "cpp"
    main = tmp_path / "main.cpp"
    main.write_text(MAIN, encoding="utf-8")
    exe = tmp_path / "main"
    cc = subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-O0", "-I", str(pkg / "include"),
                         str(main), str(pkg / "src" / "types.cpp"), "-o", str(exe), "-lfastrtps", "-lfastcdr"],
                        capture_output=True, text=True, timeout=300)
    assert cc.returncode == 0, cc.stderr[-6000:]
    out = subprocess.run([str(exe)], capture_output=True, text=True, timeout=30).stdout.split()
    assert out == [TXT_VALUE.encode().hex(), str(-2**63), "1", "1", "bound", "m::K"]


def test_unsupported_constructs_are_located_errors_and_nothing_is_written(tmp_path):
    idl = ("module m {\n"
           "  bitmask F { A, B };\n"
           "  struct S {\n"
           "    wstring w;\n"
           "    map<long, long> mp;\n"
           "    @optional long o;\n"
           "    long fine;\n"
           "  };\n"
           "};\n")
    res = _generate(tmp_path, idl)
    assert res.returncode == 1, res.stderr
    lines = [ln for ln in res.stderr.splitlines() if "error[RG1702]" in ln]
    assert [ln.split(":")[1] for ln in lines] == ["2", "4", "5", "6"], res.stderr
    assert "Traceback" not in res.stderr
    assert not (tmp_path / "out" / "cpp").exists()


def test_cpp_escapes():
    for text in ["", "plain", 'q"\\?', "a??/b", "\x00\x01\n\x7f", "é火🚀", "1\x012"]:
        lit = escape.cpp_str(text)
        assert lit.isascii() and "??" not in lit and "\n" not in lit
        body = lit[1:-1].replace("\\?", "?").replace('\\"', '"')
        # octal escapes are exactly 3 digits: decode them and the rest as written
        out, i = bytearray(), 0
        while i < len(body):
            if body[i] == "\\" and body[i + 1] == "\\":
                out += b"\\"
                i += 2
            elif body[i] == "\\":
                out.append(int(body[i + 1:i + 4], 8))
                i += 4
            else:
                out += body[i].encode()
                i += 1
        assert bytes(out) == text.encode()
    for text in ["x */ y", "a??/", "end\\", "two\nlines", "/* open", "\x1b[31m"]:
        c = escape.cpp_comment(text)
        assert "*/" not in c and "/*" not in c and "??" not in c and "\n" not in c and not c.endswith("\\")
        assert c.isprintable()
    assert escape.cmake_name("K10 Red!") == "K10_Red_" and escape.cmake_name("9x") == "_9x"


RECURSIVE = "module m { struct Node; struct Node { long id; sequence<Node> kids; }; };\n"
DEEP_MAIN = r'''
#include <cstdio>
#include <tricky/types.hpp>
int main() {
    // 100,000 nested one-element sequences: a stack overflow unless depth is limited
    std::vector<std::uint8_t> b{0, 1, 0, 0};
    for (int i = 0; i < 100000; ++i) { b.insert(b.end(), {0, 0, 0, 0, 1, 0, 0, 0}); }
    try { rapidgen::cdr::deserialize<m::Node>(b); std::printf("decoded\n"); }
    catch (const rapidgen::cdr::DecodeError& e) { std::printf("%s\n", e.what()); }
    m::Node n;
    n.kids.resize(1);
    n.kids[0].id = 5;
    std::printf("%d\n", rapidgen::cdr::deserialize<m::Node>(rapidgen::cdr::serialize(n)) == n ? 1 : 0);
}
'''


def test_recursive_type_round_trips_and_deep_nesting_is_refused(tmp_path):
    res = _generate(tmp_path, RECURSIVE)
    assert res.returncode == 0, res.stderr
    pkg = tmp_path / "out" / "cpp"
    (tmp_path / "main.cpp").write_text(DEEP_MAIN, encoding="utf-8")
    cc = subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-O1", "-I", str(pkg / "include"),
                         str(tmp_path / "main.cpp"), str(pkg / "src" / "types.cpp"), "-o", str(tmp_path / "main")],
                        capture_output=True, text=True, timeout=300)
    assert cc.returncode == 0, cc.stderr[-6000:]
    run = subprocess.run([str(tmp_path / "main")], capture_output=True, text=True, timeout=30)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == ["nesting deeper than 100 levels at offset 800", "1"]
