"""Preprocessor: includes, guards, conditionals, macros, pragmas and line mapping."""
import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.idl.preprocess import preprocess
from tests.helpers import errors_of, ir_of, rapidgen


def names(ir):
    return [d["name"] for d in ir["declarations"]]


def run(tmp_path, files: dict[str, str], main="main.idl", include=()):
    for rel, text in files.items():
        p = tmp_path / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    sink = DiagnosticSink()
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        pre = preprocess([main], list(include), sink)
    finally:
        os.chdir(cwd)
    return pre, sink


def test_quoted_include_prefers_including_folder(tmp_path):
    pre, sink = run(tmp_path, {
        "main.idl": '#include "sub/a.idl"\n',
        "sub/a.idl": '#include "b.idl"\n',
        "sub/b.idl": "module near { struct S { long x; }; };\n",
        "inc/b.idl": "module far { struct S { long x; }; };\n",
    }, include=["inc"])
    assert not sink.diagnostics
    assert "near" in pre.text and "far" not in pre.text


def test_angle_include_uses_search_path_first(tmp_path):
    pre, sink = run(tmp_path, {
        "main.idl": "#include <b.idl>\n",
        "b.idl": "module near { struct S { long x; }; };\n",
        "inc/b.idl": "module far { struct S { long x; }; };\n",
    }, include=["inc"])
    assert not sink.diagnostics
    assert "far" in pre.text and "near" not in pre.text


def test_file_included_twice_by_different_paths_is_read_once(tmp_path):
    pre, sink = run(tmp_path, {
        "main.idl": '#include "a/T.idl"\n#include "b/../a/T.idl"\n#include <T.idl>\n',
        "a/T.idl": "module m { struct T { long x; }; };\n",
        "b/README": "",
    }, include=["a"])
    assert not sink.diagnostics
    assert pre.text.count("struct T") == 1
    assert pre.files == ["main.idl", os.path.join("a", "T.idl")]


def test_include_guards_and_conditionals(tmp_path):
    src = """#ifndef G
#define G
#define FEATURE 2
#if defined(FEATURE) && FEATURE > 1
module yes1 { struct A { long a; }; };
#elif 1
module no1 { struct A { long a; }; };
#else
module no2 { struct A { long a; }; };
#endif
#ifdef MISSING
module no3 { struct A { long a; }; };
#elif !defined MISSING
module yes2 { struct A { long a; }; };
#endif
#undef FEATURE
#ifdef FEATURE
module no4 { struct A { long a; }; };
#endif
#if 0
#if 1
module no5 { struct A { long a; }; };
#endif
#else
module yes3 { struct A { long a; }; };
#endif
#endif
"""
    ir = ir_of(tmp_path, src)
    assert sorted({n.split("::")[0] for n in names(ir)}) == ["yes1", "yes2", "yes3"]


def test_directives_inside_comments_are_not_preprocessed(tmp_path):
    src = """/*
#include "missing.idl"
#error not here
*/
//@copy-c-declaration #if SOMETHING
//@copy-c-declaration #include <nothing.h>
module m { struct S { long x; }; };
//@copy-c-declaration #endif
"""
    ir = ir_of(tmp_path, src)
    assert names(ir) == ["m::S"]


def test_object_macro_is_expanded_outside_strings(tmp_path):
    src = '#define N 8\nmodule m { const string NAME = "N"; typedef sequence<long, N> Seq; };\n'
    ir = ir_of(tmp_path, src)
    decls = {d["name"]: d for d in ir["declarations"]}
    assert decls["m::Seq"]["type"] == "sequence<long, 8>"
    assert decls["m::NAME"]["value"] == "N"


def test_command_line_define(tmp_path):
    src = "#ifdef WITH_B\nmodule b { struct B { long x; }; };\n#endif\nmodule a { struct A { long x; }; };\n"
    assert names(ir_of(tmp_path, src)) == ["a::A"]
    assert names(ir_of(tmp_path, src, "t.idl", "-DWITH_B")) == ["b::B", "a::A"]


def test_unknown_pragma_is_a_warning_and_keylist_is_kept(tmp_path):
    pre, sink = run(tmp_path, {"main.idl": "#pragma once\n#pragma keylist m::S x\n"})
    assert [d.code for d in sink.diagnostics] == ["RG0110"]
    assert "#pragma keylist m::S x" in pre.text


def test_errors_in_included_file_name_that_file_and_line(tmp_path):
    (tmp_path / "inc").mkdir()
    (tmp_path / "inc" / "Bad.idl").write_text("module m {\n  struct S {\n    Unknwn x;\n  };\n};\n")
    res = errors_of(tmp_path, '// leading comment\n#include "Bad.idl"\nmodule n { struct T { long y; }; };\n',
                    "t.idl", "-I", "inc")
    assert res.code == 1
    assert res.err.startswith(os.path.join("inc", "Bad.idl") + ":3:5: error[RG0203]: unknown type 'Unknwn'")


def test_error_directive(tmp_path):
    res = errors_of(tmp_path, "#ifndef CONFIGURED\n#error set CONFIGURED first\n#endif\n")
    assert res.code == 1
    assert "t.idl:2:1: error[RG0109]: #error set CONFIGURED first" in res.err


@pytest.mark.parametrize("src,code", [
    ("#if 1\nmodule m { struct S { long x; }; };\n", "RG0104"),
    ("#endif\n", "RG0104"),
    ("#frobnicate\n", "RG0105"),
    ("#if 1 +\n#endif\n", "RG0106"),
    ("#define F(x) x\n", "RG0107"),
    ('#include "nowhere.idl"\n', "RG0101"),
])
def test_preprocessor_errors(tmp_path, src, code):
    res = errors_of(tmp_path, src)
    assert res.code == 1
    assert f"error[{code}]" in res.err
    assert "Traceback" not in res.err


def test_include_cycle_is_an_error(tmp_path, monkeypatch):
    (tmp_path / "a.idl").write_text('#include "b.idl"\nmodule a { struct A { long x; }; };\n')
    (tmp_path / "b.idl").write_text('#include "a.idl"\nmodule b { struct B { long x; }; };\n')
    monkeypatch.chdir(tmp_path)
    res = rapidgen("ir", "a.idl")
    assert res.code == 1
    assert "b.idl:1:1: error[RG0102]: include cycle: a.idl -> b.idl -> a.idl" in res.err


@pytest.mark.parametrize("expr,value", [
    ("A & 4 == 4", 6 & 1),  # C: == binds tighter than &
    ("(A & 4) == 4", 1),
    ("A | 1 ^ 3 & 2", 6 | (1 ^ (3 & 2))),
    ("0 && 1/0", 0),  # short-circuit: the right side is not computed
    ("1 || 1 % 0", 1),
    ("3 > 2 > 1", 0),  # left to right: (3 > 2) > 1
    ("-7 / 2 * 2 + -7 % 2", -7),  # truncation toward zero
    ("!A + ~0", -1),
    ("C << 1", 24),  # macros evaluate their values
    ("UNDEFINED + EMPTY", 0),
])
def test_if_expressions_follow_c(expr, value):
    from rapidgen.idl.ifexpr import evaluate
    assert evaluate(expr, {"A": "6", "C": "A * 2", "EMPTY": ""}) == value


# -- plain lines in one piece (issue 26) ------------------------------------------------------
_LINES = ["struct S { long x; };", "  module m {", "};", "", "   ", "#define N 3", "#define E",
          "#ifdef E", "#ifndef N", "#else", "#endif", "#undef N", "long a[N];", "/* open", "still */ long b;",
          "// note", "long k; //@key", 'const string s = "a/b";', "char c = '#';", "x\r", "\f# define F 1",
          "#if 0", "typedef long T; /* c */ typedef T U;"]


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.sampled_from(_LINES), max_size=40), st.booleans())
def test_plain_lines_in_one_piece_are_what_line_by_line_makes(tmp_path, picked, final_newline):
    import re

    from rapidgen.idl import preprocess as module

    text = "\n".join(picked) + ("\n" if final_newline else "")
    (tmp_path / "main.idl").write_text(text, encoding="utf-8", newline="")

    def run_with(pattern):
        old = module._NOT_PLAIN
        module._NOT_PLAIN = pattern
        try:
            pre, sink = run(tmp_path, {}, "main.idl")
        finally:
            module._NOT_PLAIN = old
        lines = [pre.line_map[i] for i in range(len(pre.line_map))]
        return pre.text, lines, dict(pre.key_comments), [(d.code, d.message, d.loc) for d in sink.diagnostics]

    fast = run_with(module._NOT_PLAIN)
    assert fast == run_with(re.compile(r"[\s\S]"))  # every line looked at, one by one
