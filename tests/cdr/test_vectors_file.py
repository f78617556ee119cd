"""tests/vectors/rapid.json is generated: regenerating it must give the same bytes (the
CI staleness check for the golden vectors), on every run."""
from __future__ import annotations

import difflib
import json
import os

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.vectors import COMMITTED, COMMITTED_COMMAND, render
from tests.cdr.conftest import ROOT, seed_assets
from tests.helpers import rapidgen


def _regenerate(monkeypatch) -> str:
    monkeypatch.chdir(ROOT)
    sink = DiagnosticSink()
    text = render(seed_assets(), [], sink)
    assert text is not None, [str(d) for d in sink.diagnostics]
    return text


def test_committed_vectors_are_up_to_date(monkeypatch):
    text = _regenerate(monkeypatch)
    with open(os.path.join(ROOT, COMMITTED), encoding="utf-8") as fh:
        committed = fh.read()
    if text != committed:
        diff = "".join(list(difflib.unified_diff(committed.splitlines(True), text.splitlines(True),
                                                 COMMITTED, "regenerated", n=0))[:40])
        raise AssertionError(f"{COMMITTED} is stale; rerun `{COMMITTED_COMMAND}`\n{diff[:4000]}")


def test_generation_is_deterministic(monkeypatch):
    assert _regenerate(monkeypatch) == _regenerate(monkeypatch)


def test_cli_writes_the_file(tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)
    out = tmp_path / "v.json"
    res = rapidgen("vectors", "-I", "specs/rapid", "specs/rapid/Ack.idl", "specs/rapid/Header.idl", "-o", str(out))
    assert res.code == 0, res.err
    assert "vectors, written" in res.out
    data = json.loads(out.read_text(encoding="utf-8"))
    assert {"rapid::Ack", "rapid::Header", "rapid::Message"} <= {v["type"] for v in data["vectors"]}
    assert "rapid::Command" not in {v["type"] for v in data["vectors"]}
    again = rapidgen("vectors", "-I", "specs/rapid", "specs/rapid/Ack.idl", "specs/rapid/Header.idl", "-o", str(out))
    assert "unchanged" in again.out


def test_cli_reports_input_errors(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.idl").write_text("module m { struct S { Missing x; }; };\n", encoding="utf-8")
    res = rapidgen("vectors", "bad.idl", "-o", "v.json")
    assert res.code == 1
    assert "unknown type" in res.err
    assert not (tmp_path / "v.json").exists()


def test_merging_inputs_refuses_conflicting_declarations(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.idl").write_text("module m { struct S { long x; }; };\n", encoding="utf-8")
    (tmp_path / "b.idl").write_text("module m { struct S { short x; }; };\n", encoding="utf-8")
    from rapidgen.idl.load import load_idl
    from rapidgen.vectors import merge_models

    sink = DiagnosticSink()
    a, _ = load_idl(["a.idl"], [], sink)
    b, _ = load_idl(["b.idl"], [], sink)
    assert merge_models([a, b], sink) is None
    assert any("declared differently" in d.message for d in sink.diagnostics)
    same, _ = load_idl(["a.idl"], [], DiagnosticSink())
    assert merge_models([a, same], DiagnosticSink()) is not None
