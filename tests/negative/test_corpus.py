"""The negative corpus: malformed inputs and the exact diagnostics they must produce.

Each folder under cases/ holds `input.idl` (plus any files it includes) and
`expected.txt`, the exact stderr of `rapidgen ir input.idl` run from that folder. An
optional `case.json` gives the expected exit code (default 1) and extra arguments:
`{"exit": 0, "args": ["-I", "inc"]}`. Rewrite the expectations after a deliberate
change with `pytest tests/negative --update-golden`, then review the diff by eye.

Inputs too big to commit (10 MB) are generated at run time by the tests at the end.
"""
from __future__ import annotations

import json
import random
import re
from pathlib import Path

import pytest

from tests.helpers import assert_golden, rapidgen

CASES = Path(__file__).parent / "cases"
CASE_DIRS = sorted(p for p in CASES.iterdir() if p.is_dir())

# file:line:col: severity[CODE]: message
DIAG = re.compile(r"^(?P<file>[^:\n]+):(?P<line>\d+):(?P<col>\d+): (?P<sev>error|warning|note)\[(?P<code>RG\d{4})\]: ")


def _meta(case: Path) -> dict:
    meta = {"exit": 1, "args": []}
    path = case / "case.json"
    if path.exists():
        meta.update(json.loads(path.read_text(encoding="utf-8")))
    return meta


def assert_no_crash(err: str) -> None:
    assert "Traceback" not in err, err
    assert "internal error" not in err, err


def test_corpus_is_big_enough():
    assert len(CASE_DIRS) >= 45


@pytest.mark.parametrize("case", CASE_DIRS, ids=[p.name for p in CASE_DIRS])
def test_case(case: Path, monkeypatch, update_golden):
    meta = _meta(case)
    monkeypatch.chdir(case)
    res = rapidgen("ir", *meta["args"], "input.idl")
    assert_no_crash(res.err)
    assert res.code == meta["exit"], f"exit {res.code}, expected {meta['exit']}\n{res.err}"

    assert_golden(case / "expected.txt", res.err, update_golden, "stderr")

    # Every diagnostic names a file of the case (relative, as the user typed or included it).
    diags = [m for m in map(DIAG.match, res.err.splitlines()) if m]
    assert diags, "no diagnostic at all"
    for m in diags:
        assert (case / m["file"]).is_file(), f"diagnostic names '{m['file']}', which is not a file of the case"
        assert int(m["line"]) >= 1 and int(m["col"]) >= 1, m.group(0)
    errors = [m for m in diags if m["sev"] == "error"]
    assert bool(errors) == (meta["exit"] == 1), "errors must go with exit 1, warnings alone with exit 0"
    assert res.err.rstrip("\n").splitlines()[-1].startswith("rapidgen: "), "the summary line is missing"


# -- valid counterparts that must stay out of the negative corpus --------------------------

def test_recursion_through_sequence_is_valid(tmp_path, monkeypatch):
    (tmp_path / "ok.idl").write_text(
        "struct Node {\n  long value;\n  sequence<Node> children;\n};\n"
        "struct Tree;\nstruct Branch {\n  sequence<Tree, 4> subtrees;\n};\n"
        "struct Tree {\n  Branch root;\n  Node nodes[2];\n};\n", encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("ir", "--no-loc", "ok.idl")
    assert res.code == 0, res.err
    assert res.err == ""
    names = [d["name"] for d in json.loads(res.out)["declarations"]]
    assert set(names) == {"Node", "Branch", "Tree"}


def test_nested_template_closing_shift_is_valid(tmp_path, monkeypatch):
    """`>>` closes two template lists (as in C++11); one level deep it is still a shift."""
    (tmp_path / "ok.idl").write_text(
        "const long N = 8 >> 1;\n"
        "struct S {\n  sequence<sequence<long>> grid;\n  map<long, sequence<string<8>>> names;\n"
        "  sequence<long, N >> 1> half;\n};\n", encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("ir", "--no-loc", "ok.idl")
    assert (res.code, res.err) == (0, ""), res.err
    decls = {d["name"]: d for d in json.loads(res.out)["declarations"]}
    assert decls["N"]["value"] == 4
    assert [m["type"] for m in decls["S"]["members"]] == [
        "sequence<sequence<long>>", "map<long, sequence<string<8>>>", "sequence<long, 2>"]


def test_warning_can_be_silenced(monkeypatch):
    monkeypatch.chdir(CASES / "annotation_unknown_warning_only")
    res = rapidgen("ir", "-W", "no-RG0501", "input.idl")
    assert (res.code, res.err) == (0, "")


def test_warnings_as_errors(monkeypatch):
    monkeypatch.chdir(CASES / "annotation_unknown_warning_only")
    res = rapidgen("ir", "-W", "error", "input.idl")
    assert res.code == 1
    assert "input.idl:2:3: error[RG0501]" in res.err


# -- 10 MB inputs, generated at run time -------------------------------------------------------

TEN_MB = 10 * 1024 * 1024


def test_ten_megabytes_of_structs_then_one_error(tmp_path, monkeypatch):
    chunk = ("struct Sample{n} {{\n  long id; //@key\n  double values[4];\n  string<32> name;\n"
             "  sequence<long, 16> samples;\n}};\n")
    parts, size, n = [], 0, 0
    while size < TEN_MB:
        text = chunk.format(n=n)
        parts.append(text)
        size += len(text)
        n += 1
    parts.append("struct Broken {\n  long a\n  long b;\n};\n")
    source = "".join(parts)
    bad_line = source.count("\n", 0, source.index("long a\n")) + 1
    (tmp_path / "big.idl").write_text(source, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("ir", "big.idl")
    assert_no_crash(res.err)
    assert res.code == 1
    assert res.err.splitlines()[0] == f"big.idl:{bad_line}:9: error[RG0201]: expected ';' before 'long'"
    assert res.err.count("error[") == 1


def test_ten_megabytes_of_garbage_on_one_line(tmp_path, monkeypatch):
    rng = random.Random(20240611)
    alphabet = "abcxyz019 {}<>;:,=+-*/%&|^~()[]@#$?!.\t"
    (tmp_path / "garbage.idl").write_text("".join(rng.choices(alphabet, k=TEN_MB)), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("ir", "garbage.idl")
    assert_no_crash(res.err)
    assert res.code == 1
    assert re.match(r"garbage\.idl:1:\d+: error\[RG\d{4}\]", res.err), res.err[:500]
    assert len(res.err) < 4096, "the excerpt of a huge line must be cut short"
