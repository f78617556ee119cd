"""Hostile IDL inputs end quickly with a located error (issue 8: front-end resource bounds).

Each input is built here, in tmp_path, and run through `rapidgen ir` in a child bounded
by tests/hostile/limits.py: a case that needs more memory or CPU than the fence is
killed, which fails the test. Each must exit 1 with file:line:col and its code.
"""
from __future__ import annotations

import re

import pytest

from tests.hostile.limits import run_rapidgen

MiB = 1024 * 1024
MEM, CPU = 1024, 20


def run_ir(tmp_path, text: str, name: str = "input.idl", mem_mib: int = MEM):
    (tmp_path / name).write_text(text, encoding="utf-8")
    return run_rapidgen("ir", name, cwd=tmp_path, mem_mib=mem_mib, cpu_s=CPU)


def assert_located(res, code: str, line: int | None = None, col: int | None = None,
                   name: str = "input.idl") -> None:
    assert not res.killed, f"killed by signal {-res.code}: {res.err[-500:]}"
    assert "Traceback" not in res.err and "internal error" not in res.err, res.err[-2000:]
    assert res.code == 1, res.err[-2000:]
    line_re, col_re = (str(n) if n is not None else r"\d+" for n in (line, col))
    assert re.search(rf"^{re.escape(name)}:{line_re}:{col_re}: error\[{code}\]", res.err, re.M), res.err[:2000]


def assert_ok(res) -> None:
    assert not res.killed, f"killed by signal {-res.code}: {res.err[-500:]}"
    assert res.code == 0, res.err[-2000:]


# -- 5: macros that double at each level ------------------------------------------------

def doubling_macros(levels: int) -> list[str]:
    return ["#define A0 1"] + [f"#define A{i} A{i - 1}+A{i - 1}" for i in range(1, levels + 1)]


def test_doubling_macro_chain_is_capped(tmp_path):
    text = "\n".join(doubling_macros(22) + ["const long X = A22;"]) + "\n"
    res = run_ir(tmp_path, text)
    assert_located(res, "RG0113", 24, 16)
    assert "macro 'A22' expands to more than" in res.err


def test_fanning_out_macro_chain_in_if_is_linear(tmp_path):
    # #if evaluates each macro once: A10 would otherwise take 8**10 evaluations.
    lines = ["#define A0 1"] + [f"#define A{i} " + "+".join([f"A{i - 1}"] * 8) for i in range(1, 11)]
    text = "\n".join(lines + [f"#if A10 == {8 ** 10}", "const long X = 1;", "#else",
                               "#error wrong value", "#endif"]) + "\n"
    assert_ok(run_ir(tmp_path, text))


def test_macro_expansions_are_capped_in_total(tmp_path):
    # Each use stays under the per-use cap; together they would add gigabytes.
    big = "+".join(["B"] * 8000)  # ~16 KiB
    lines = ["#define B 1", f"#define M {big}", "const long X = 0"]
    lines += ["+ M " * 100] * 5_000
    lines += [";"]
    res = run_ir(tmp_path, "\n".join(lines) + "\n")
    assert_located(res, "RG0113")
    assert "macro expansions add more than" in res.err


def test_long_continued_directive_is_refused(tmp_path):
    text = "#define X 1 \\\n" + "1 \\\n" * 200_000 + "\nconst long Y = 1;\n"
    res = run_ir(tmp_path, text)
    assert_located(res, "RG0107", 1, 1)
    assert "longer than" in res.err


# -- 6: huge strings and comments lex in linear memory ----------------------------------

def at_size_limit(prefix: str, fill: str, suffix: str) -> str:
    from rapidgen.idl.preprocess import MAX_INPUT_BYTES
    room = MAX_INPUT_BYTES - len(prefix) - len(suffix)
    return prefix + fill * (room // len(fill)) + suffix


@pytest.mark.parametrize("make", [
    lambda: at_size_limit('const string S = "', "a", '";\n'),
    lambda: at_size_limit("struct S { long x; };\n/*", "a", "*/\n"),
    lambda: at_size_limit("struct S { long x; };\n/*", "a\n", "*/\n"),
    lambda: at_size_limit("struct S { long x; };\n/*", "*", "*/\n"),
], ids=["string", "comment", "comment-lines", "comment-stars"])
def test_file_at_size_limit_of_one_string_or_comment(tmp_path, make):
    # Fails (exit 1 with a located error) only if some input problem is found: here none;
    # before the fix the regex engine's stack grew per character (gigabytes).
    (tmp_path / "input.idl").write_text(make(), encoding="utf-8")
    res = run_rapidgen("ir", "input.idl", "-o", "out.json", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    assert_ok(res)


def test_unterminated_comment_at_size_limit(tmp_path):
    res = run_ir(tmp_path, at_size_limit("struct S { long x; };\n/*", "a\n", ""))
    assert_located(res, "RG0108", 2, 1)


def test_escaped_string_lexes_in_linear_memory(tmp_path):
    res = run_ir(tmp_path, 'const string S = "' + "\\n" * (4 * MiB) + '";\nconst long X = Y;\n')
    assert_located(res, "RG0203", 2, 16)  # got past the string to a real error


def test_input_files_together_are_capped(tmp_path):
    from rapidgen.idl.preprocess import MAX_INPUT_BYTES
    chunk = "/*" + "a" * (MAX_INPUT_BYTES // 2) + "*/\n"
    for i in range(3):
        (tmp_path / f"f{i}.idl").write_text(chunk, encoding="utf-8")
    (tmp_path / "input.idl").write_text('#include "f0.idl"\n#include "f1.idl"\n#include "f2.idl"\n')
    res = run_rapidgen("ir", "input.idl", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    assert_located(res, "RG0005", 3, 1)


# -- 9: thousands of cases, enumerators, misspelt names ------------------------------------

def test_union_with_many_cases_and_one_duplicate(tmp_path):
    n = 20_000
    body = "".join(f"case {i}: long m{i};\n" for i in range(n))
    res = run_ir(tmp_path, f"union U switch (long) {{\n{body}case 7: long dup;\n}};\n")
    assert_located(res, "RG0304", n + 2, 6)


def test_union_over_enum_with_many_cases(tmp_path):
    n = 20_000
    enum = "enum E {\n" + ",\n".join(f"e{i}" for i in range(n)) + "\n};\n"
    body = "".join(f"case e{i}: long m{i};\n" for i in range(n))
    res = run_ir(tmp_path, f"{enum}union U switch (E) {{\n{body}case e3: long m3;\n}};\n")
    assert_located(res, "RG0304", 2 * n + 4, 6)


def test_many_unknown_names(tmp_path):
    n = 20_000
    text = "".join(f"struct T{i} {{ long x; }};\n" for i in range(n))
    text += "struct S {\n" + "".join(f"Q{i} m{i};\n" for i in range(n)) + "};\n"
    res = run_ir(tmp_path, text)
    assert_located(res, "RG0203", n + 2, 1)


# -- 10: long numeric literals ------------------------------------------------------------

@pytest.mark.parametrize("literal", ["9" * 5000, "9" * 1_000_000, "0x" + "f" * 100_000, "1" * 41])
def test_integer_literal_too_long(tmp_path, literal):
    res = run_ir(tmp_path, f"const long long X = {literal};\n")
    assert_located(res, "RG0402", 1, 21)
    assert "too large for any IDL type" in res.err


def test_long_digit_run_lexes_in_linear_time(tmp_path):
    # Before: the fixed-point pattern backtracked over every split of the digits.
    res = run_ir(tmp_path, "const double X = " + "9" * 2_000_000 + ".5;\nconst long Y = Z;\n")
    assert_located(res, "RG0203", 2, 16)


def test_fixed_literal_too_long(tmp_path):
    res = run_ir(tmp_path, "const fixed F = " + "1" * 40 + ".5d;\n")
    assert_located(res, "RG0402", 1, 17)


def test_literals_with_leading_zeros_still_fit(tmp_path):
    (tmp_path / "input.idl").write_text(
        "const long long X = 0" + "0" * 60 + "12;\n"
        "const unsigned long long H = 0x" + "0" * 60 + "FFFFFFFFFFFFFFFF;\n"
        "const fixed F = 000123.4500d;\n")
    res = run_rapidgen("ir", "--no-loc", "input.idl", cwd=tmp_path, cpu_s=CPU)
    assert_ok(res)
    assert '"value": 10' in res.out and '"value": 18446744073709551615' in res.out


# -- other nesting ---------------------------------------------------------------------------

def test_deeply_nested_modules(tmp_path):
    n = 100_000
    res = run_ir(tmp_path, "module m { " * n + "struct S { long x; };" + " };" * n + "\n")
    assert_located(res, "RG0201", 1)
    assert "nested more than" in res.err


@pytest.mark.parametrize("expr", ["(" * 30_000 + "1" + ")" * 30_000, "-" * 30_000 + "1"])
def test_deeply_nested_if_expression(tmp_path, expr):
    res = run_ir(tmp_path, f"#if {expr}\nconst long X = 1;\n#endif\n")
    assert_located(res, "RG0106", 1, 1)


def test_very_long_constant_expression(tmp_path):
    res = run_ir(tmp_path, "const long X = " + "1+" * 200_000 + "1;\n")
    assert_located(res, "RG0201", 1)
