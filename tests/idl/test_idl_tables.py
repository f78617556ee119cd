"""The IDL grammar's packaged LALR tables (rapidgen/idl/packaged_tables.py): fresh, the
same whatever order lark's sets come out in, parsing exactly as lark's own parser does
with the same syntax-tree builder, and no lark imported on the way to a model."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from lark import Lark

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.idl import grammar, larkgrammar, packaged_tables
from rapidgen.idl import parse as parse_mod
from rapidgen.idl.lalr import LeanLALR
from rapidgen.idl.preprocess import preprocess

REPO = Path(__file__).resolve().parents[2]
CORPUS = sorted((REPO / "specs").rglob("*.idl"))


def test_packaged_tables_are_fresh():
    path = Path(grammar.__file__).resolve().parent / grammar.PACKAGED_MODULE
    assert path.read_text(encoding="utf-8") == larkgrammar.packaged_module_text(), \
        "stale: run `python -m rapidgen.idl.larkgrammar --write`"
    assert grammar.tables() is packaged_tables.TABLES


def test_tables_do_not_depend_on_hash_order():
    """lark numbers its states in the order of its sets (string hashes differ per process);
    the tables are numbered canonically, so any process writes the same module."""
    code = ("import hashlib, pprint, functools; from lark import Lark; import rapidgen.idl.larkgrammar as L\n"
            "L.parser = functools.lru_cache(maxsize=1)(lambda: Lark(L.grammar_text(), parser='lalr', "
            "lexer=L.LarkLexer, maybe_placeholders=False))\n"
            "print(hashlib.sha256(pprint.pformat(L.build_tables(), sort_dicts=False).encode()).hexdigest())")
    digests = set()
    for seed in ("1", "2"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        proc = subprocess.run([sys.executable, "-c", code], cwd=REPO, env=env, capture_output=True, text=True,
                              timeout=120)
        assert proc.returncode == 0, proc.stderr
        digests.add(proc.stdout.strip())
    assert len(digests) == 1


def _pre(path: Path):
    sink = DiagnosticSink()
    pre = preprocess([str(path)], [str(REPO / "specs" / "rapid"), str(path.parent)], sink)
    return pre, sink


@pytest.mark.parametrize("path", CORPUS[:40], ids=lambda p: p.name)
def test_lean_parse_equals_lark_s_own(path):
    """The same builder driven by lark's parser (its tree builder shaping the children) and
    by the lean driver over the packaged tables gives equal syntax trees."""
    pre, sink = _pre(path)
    assert not sink.has_errors, sink.diagnostics
    ours = parse_mod.parse(pre, DiagnosticSink())
    builder = parse_mod._ToAst(parse_mod._Locator(pre), pre.key_comments, DiagnosticSink())
    lark_s = Lark(grammar.grammar_text(), parser="lalr", lexer=larkgrammar.LarkLexer, maybe_placeholders=False,
                  transformer=builder).parse(pre.text)
    assert ours is not None
    assert ours.definitions == tuple(d for d in lark_s if d is not None)


def test_stale_packaged_tables_are_not_used(monkeypatch, tmp_path):
    monkeypatch.setattr(packaged_tables, "GRAMMAR", "start: other")
    built = grammar.tables()
    assert built is not packaged_tables.TABLES and built == packaged_tables.TABLES
    path = tmp_path / "a.idl"
    path.write_text("module m { struct S { long x; sequence<sequence<long>> y; }; };\n", encoding="utf-8")
    pre, _ = _pre(path)
    lean = LeanLALR(built, grammar.lark_parser)
    spec = lean.parse(pre.text, parse_mod._ToAst(parse_mod._Locator(pre), pre.key_comments, DiagnosticSink()))
    assert spec[0].name == "m"


def test_a_model_is_made_without_lark_and_an_error_still_explained(tmp_path):
    good, bad = tmp_path / "good.idl", tmp_path / "bad.idl"
    good.write_text("module m { struct S { long x; //@key\n string<8> s; }; };\n", encoding="utf-8")
    bad.write_text("module m { struct S { long x }; };\n", encoding="utf-8")
    code = ("import sys\nfrom rapidgen.diagnostics import DiagnosticSink\nfrom rapidgen.idl.load import load_idl\n"
            "sink = DiagnosticSink()\nmodel, _ = load_idl([sys.argv[1]], [], sink)\n"
            "print(model is not None, 'lark' in sys.modules, [d.code for d in sink.diagnostics], "
            "[(d.loc.line, d.loc.col) for d in sink.diagnostics])")
    runs = [subprocess.run([sys.executable, "-c", code, str(p)], cwd=REPO, capture_output=True, text=True,
                           timeout=120) for p in (good, bad)]
    assert [r.returncode for r in runs] == [0, 0], [r.stderr for r in runs]
    assert runs[0].stdout.split("\n")[0] == "True False [] []"
    # the syntax error: lark's parser is loaded to explain it, at the token after `x`
    assert runs[1].stdout.split("\n")[0] == "False True ['RG0201'] [(1, 29)]"


def _lexed(text: str, every: bool = True) -> list[tuple]:
    lexer = parse_mod._lean().lexer
    return [(kind, tok and (str(tok), tok.line, tok.column, tok.start_pos, tok.end_pos))
            for kind, tok in lexer.lex(text, every=every)]


def test_lexer_skips_space_and_comments_and_places_tokens():
    text = "  // a comment / with slashes\n/* block\n * over lines */ x /* c */ / 2 // end\n  \n"
    assert _lexed(text) == [("IDENT", ("x", 3, 18, 56, 57)), ("BINOP", ("/", 3, 28, 66, 67)),
                            ("INT_LIT", ("2", 3, 30, 68, 69))]
    assert _lexed("") == [] and _lexed(" \n// only a comment") == []
    # punctuation no rule keeps: its name only, unless every token is asked for
    assert _lexed("x;", every=False) == [("IDENT", ("x", 1, 1, 0, 1)), ("SEMICOLON", None)]
    # two template lists closed by one '>>'
    assert [k for k, _ in _lexed("sequence<sequence<long>> s;")] == \
        ["SEQUENCE_KW", "LESSTHAN", "SEQUENCE_KW", "LESSTHAN", "LONG_KW", "MORETHAN", "MORETHAN", "IDENT", "SEMICOLON"]


@pytest.mark.parametrize("text, where", [("x\n  `", (2, 3, 4)), ("/* c */ `", (1, 9, 8)),
                                         ("// c\n  /* c */\n $", (3, 2, 16)), ("x /", "no error")])
def test_lexer_error_is_at_the_character_no_terminal_matches(text, where):
    from rapidgen.idl.lexer import LexError

    lexer = parse_mod._lean().lexer
    try:
        list(lexer.lex(text))
    except LexError as exc:
        assert (exc.line, exc.column, exc.pos) == where
    else:
        assert where == "no error"
