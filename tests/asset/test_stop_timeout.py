"""The descriptor's per-command stop bound (`stop_timeout_ms`, issue 42): read into the
spec, carried into the Python tables and the C++ tables only where declared, and refused
when it is not a whole number of milliseconds >= 1."""
import pytest

from rapidgen.asset import load_asset
from rapidgen.backends.cpp.bridge import _tables as cpp_tables
from rapidgen.backends.python.asset_tables import tables as py_tables
from rapidgen.diagnostics import DiagnosticSink
from tests.asset.conftest import ROOT

RAPID = str(ROOT / "specs" / "rapid")

DESCRIPTOR = ("version: 1\nasset: {{name: A, kind: rover}}\nsubsystem_types:\n"
              "  - name: T\n    commands:\n"
              "      - {{name: slow, abortable: true{bound}}}\n"
              "      - {{name: quick}}\n"
              "subsystems: [{{name: S, type: T}}]\n")


def _load(tmp_path, bound: str):
    (tmp_path / "a.yaml").write_text(DESCRIPTOR.format(bound=bound))
    sink = DiagnosticSink()
    return load_asset(str(tmp_path / "a.yaml"), sink, RAPID), sink


def test_declared_bound_reaches_both_tables(tmp_path):
    loaded, sink = _load(tmp_path, ", stop_timeout_ms: 750")
    assert not sink.diagnostics
    slow, quick = loaded.spec.subsystem_types[0].commands
    assert (slow.stop_timeout_ms, quick.stop_timeout_ms) == (750, None)

    data = py_tables(loaded)
    assert data["COMMANDS"]["T"]["slow"]["stop_timeout_ms"] == 750
    assert "stop_timeout_ms" not in data["COMMANDS"]["T"]["quick"]  # absent: the bridge's default
    from rapid_runtime.tables import Tables
    t = Tables(data)
    assert t.command("S", "slow").stop_timeout_ms == 750
    assert t.command("S", "quick").stop_timeout_ms is None

    lines = cpp_tables(loaded, {})
    slow_line = next(i for i, ln in enumerate(lines) if ln.strip() == '{"slow", {')
    quick_line = next(i for i, ln in enumerate(lines) if ln.strip() == '{"quick", {')
    assert lines[slow_line + 1].endswith(", /* stop_timeout_ms */ 750},")
    assert "stop_timeout_ms" not in lines[quick_line + 1]


@pytest.mark.parametrize("bound", [", stop_timeout_ms: 0", ", stop_timeout_ms: -5", ", stop_timeout_ms: 1.5",
                                   ", stop_timeout_ms: '100'", ", stop_timeout_ms: 2147483648"])
def test_bad_bound_is_refused(tmp_path, bound):
    _, sink = _load(tmp_path, bound)
    errors = [d for d in sink.diagnostics if d.severity.name == "ERROR"]
    assert errors, bound
    assert errors[0].loc.line == 6  # at the command's line
