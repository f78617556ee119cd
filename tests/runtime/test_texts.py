"""The reason and ack texts live once, in runtime/spec/texts.yaml: the files generated from it
(runtime/rapid_runtime/texts.py, runtime/cpp/include/rapid_runtime/texts.hpp) are fresh, every
text is written by both runtimes through them, and no runtime source spells one out again.
No DDS, no compiler."""
from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from rapidgen import protocol_texts as PT

ROOT = Path(__file__).resolve().parents[2]
PYTHON_DIR = ROOT / "runtime" / "rapid_runtime"
CPP_DIR = ROOT / "runtime" / "cpp"


def _python_sources() -> dict[Path, str]:
    return {p: p.read_text(encoding="utf-8") for p in sorted(PYTHON_DIR.glob("*.py")) if p != PT.PYTHON_OUT}


def _cpp_sources() -> dict[Path, str]:
    files = [p for ext in ("*.cpp", "*.hpp") for p in CPP_DIR.rglob(ext) if p != PT.CPP_OUT]
    return {p: p.read_text(encoding="utf-8") for p in sorted(files)}


def python_literals(source: str) -> list[str]:
    """The string literals of Python code (f-strings' literal parts each), docstrings left out."""
    tree = ast.parse(source)
    docs = {id(node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)}
    return [n.value for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in docs]


def cpp_literals(source: str) -> list[str]:
    """The string literals of C++ code, as written (escapes kept), adjacent ones joined;
    comments and character literals skipped."""
    out: list[str] = []
    i, n, joinable = 0, len(source), False
    while i < n:
        c, two = source[i], source[i:i + 2]
        if two == "//":
            i = source.find("\n", i)
            i = n if i < 0 else i
        elif two == "/*":
            i = source.find("*/", i + 2)
            i = n if i < 0 else i + 2
        elif c in "\"'":
            j = i + 1
            while j < n and source[j] != c:
                j += 2 if source[j] == "\\" else 1
            if c == '"':
                text = source[i + 1:j]
                if joinable:
                    out[-1] += text
                else:
                    out.append(text)
                joinable = True
            i = j + 1
            continue
        elif not c.isspace():
            joinable = False
            i += 1
            continue
        else:
            i += 1
            continue
        joinable = False
    return out


def _copies(text: PT.Text, literal: str) -> str | None:
    """The part of `text` that `literal` spells out again, or None. A text without placeholders
    is a copy when a literal is that text (prose and log lines may quote it); a template when a
    literal holds one of its pieces of a few words (single words, such as "canceled" or
    "cancelAll", are names too and are not policed)."""
    if text.constant:
        return text.template if " " in text.template and literal.strip(" '\"") == text.template else None
    return next((p for p in text.pieces if isinstance(p, str) and " " in p.strip() and len(p.strip()) >= 11
                 and p in literal), None)


@pytest.fixture(scope="module")
def table() -> list[PT.Text]:
    return PT.load_table()


def test_generated_files_are_fresh():
    assert PT.stale() == [], "python -m rapidgen.protocol_texts"
    res = subprocess.run([sys.executable, "-m", "rapidgen.protocol_texts", "--check"], cwd=ROOT,
                         capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stderr


def test_check_says_stale_and_write_refreshes(tmp_path, monkeypatch, capsys):
    py, cpp, rs = tmp_path / "texts.py", tmp_path / "texts.hpp", tmp_path / "texts.rs"
    monkeypatch.setattr(PT, "PYTHON_OUT", py)
    monkeypatch.setattr(PT, "CPP_OUT", cpp)
    monkeypatch.setattr(PT, "RUST_OUT", rs)
    monkeypatch.setattr(PT, "ROOT", tmp_path)
    assert PT.main(["--check"]) == 1 and not py.exists()
    assert PT.main([]) == 0 and PT.main(["--check"]) == 0
    cpp.write_text(cpp.read_text() + "// edited\n")
    assert PT.main(["--check"]) == 1
    assert "stale: texts.hpp" in capsys.readouterr().err


def test_generated_python_says_the_templates(table):
    from rapid_runtime import texts
    for t in table:
        if t.constant:
            assert getattr(texts, t.name) == t.template
        else:
            values = {"text": "<{}>", "count": 7, "seconds": 2.25}
            got = getattr(texts, t.name)(*[values[k].format(n) if k == "text" else values[k] for n, k in t.args])
            want = t.template
            for n, k in t.args:
                want = want.replace("{" + n + "}", {"text": f"<{n}>", "count": "7", "seconds": "2.2"}[k])
            assert got == want, t.key


def test_every_text_is_written_by_both_runtimes_through_the_generated_names(table):
    python = "\n".join(_python_sources().values())
    cpp = "\n".join(_cpp_sources().values())
    missing = []
    for t in table:
        for runtime, code, use in (("python", python, rf"\btexts\.{t.name}\b"), ("cpp", cpp, rf"\btexts::{t.name}\b")):
            used = re.search(use, code) is not None
            if t.only in (None, runtime) and not used:
                missing.append(f"{t.key}: not used by the {runtime} runtime")
            if t.only not in (None, runtime) and used:
                missing.append(f"{t.key}: only: {t.only}, but the {runtime} runtime writes it")
    assert not missing, "\n".join(missing)


def test_no_runtime_source_spells_a_text_out_again(table):
    found = []
    for sources, literals in ((_python_sources(), python_literals), (_cpp_sources(), cpp_literals)):
        for path, source in sources.items():
            for literal in literals(source):
                found += [f"{path.relative_to(ROOT)}: {literal!r} holds {t.key}'s {_copies(t, literal)!r}"
                          for t in table if _copies(t, literal)]
    assert not found, "\n".join(found)


def test_the_literal_scanners_find_what_they_must():
    # (the test above could pass on a scanner that finds nothing)
    assert python_literals('"""doc"""\nx = f"{a} source back"\n# "comment"\n') == [" source back"]
    assert cpp_literals('// "no"\nauto c = \'"\'; /* "no" */ f("queue full (" "x", "\\"q\\"");') == \
        ['queue full (x', '\\"q\\"']
    texts = {t.key: t for t in PT.load_table()}
    assert _copies(texts["queue_full"], "queue full (%d pending); retry later") == "queue full ("
    assert _copies(texts["did_not_stop"], "handler did not stop") == "handler did not stop"
    assert _copies(texts["did_not_stop"], "handler did not stop within ") is None
    assert _copies(texts["canceled"], "canceled") is None


@pytest.mark.parametrize("yaml_text, says", [
    ("texts:\n  a:\n    text: 'x {n}'\n    when: w\n", "placeholder {n} is not declared"),
    ("texts:\n  a:\n    text: 'x'\n    args: {n: count}\n    when: w\n", "placeholder n is not in the text"),
    ("texts:\n  a:\n    text: 'x {n}'\n    args: {n: number}\n    when: w\n", "type 'number'"),
    ("texts:\n  a:\n    text: 'x {str}'\n    args: {str: text}\n    when: w\n", "placeholder name 'str'"),
    ("texts:\n  Bad:\n    text: 'x'\n    when: w\n", "key 'Bad'"),
    ("texts:\n  a:\n    text: 'x }'\n    when: w\n", "a brace"),
    ("texts:\n  a:\n    text: 'x'\n", "`when` is one line"),
    ("texts:\n  a:\n    text: 'x'\n    when: w\n  A:\n    text: 'y {v}'\n    args: {v: text}\n    when: w\n", "key 'A'"),
])
def test_a_bad_table_is_refused_with_its_place(tmp_path, yaml_text, says):
    path = tmp_path / "texts.yaml"
    path.write_text(yaml_text)
    with pytest.raises(PT.TextsError) as err:
        PT.load_table(path, "texts.yaml")
    assert says in str(err.value) and re.match(r"texts\.yaml:\d+:\d+: ", str(err.value)), str(err.value)


def _c_literal_bytes(literal: str) -> bytes:
    """A C++ string literal made of printable ASCII, \\, \\" and three-digit octal escapes, read back."""
    assert literal[0] == literal[-1] == '"'
    out, body, i = bytearray(), literal[1:-1], 0
    while i < len(body):
        if body[i] != "\\":
            assert body[i] != '"', literal  # an unescaped quote would end the literal
            out.append(ord(body[i]))
            i += 1
        elif body[i + 1] in '\\"':
            out.append(ord(body[i + 1]))
            i += 2
        else:
            out.append(int(body[i + 1:i + 4], 8))
            i += 4
    return bytes(out)


def test_hostile_text_reaches_generated_code_only_as_literals(tmp_path):
    nasty = 'q"\\\' ??= \u00e9 \U0001f916 */ #x {v} """ \\x41 \\'
    path = tmp_path / "texts.yaml"
    path.write_text("texts:\n  k:\n    text: " + json.dumps(nasty, ensure_ascii=False) + "\n    args: {v: text}\n    when: w\n",
                    encoding="utf-8")
    table = PT.load_table(path, "texts.yaml")
    assert table[0].template == nasty
    space: dict = {}
    exec(compile(PT.python_source(table), "texts.py", "exec"), space)  # what importing texts.py does
    assert space["k"]("{v}") == nasty
    source = PT.cpp_source(table)
    line = next(x for x in source.splitlines() if x.startswith("inline std::string k("))
    assert [_c_literal_bytes('"' + x + '"') for x in cpp_literals(line)] == [p.encode() for p in nasty.split("{v}")]


def test_a_note_cannot_run_into_the_next_line(tmp_path):
    path = tmp_path / "texts.yaml"
    path.write_text("texts:\n  k:\n    text: x\n    when: 'ends in a backslash \\'\n", encoding="utf-8")
    with pytest.raises(PT.TextsError, match="backslash"):
        PT.load_table(path, "texts.yaml")
