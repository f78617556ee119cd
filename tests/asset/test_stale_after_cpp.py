"""stale_after_ms reaches the C++ tables only where declared (TelemetrySpec::stale_after_ms,
0: derived from the rate by the runtime, freshness.hpp), like stop_timeout_ms on commands."""
from rapidgen.asset import load_asset
from rapidgen.backends.cpp.bridge import _tables as cpp_tables
from rapidgen.diagnostics import DiagnosticSink
from tests.asset.conftest import ROOT

RAPID = str(ROOT / "specs" / "rapid")

DESCRIPTOR = """version: 1
asset: {name: A, kind: rover}
subsystem_types:
  - name: T
    commands:
      - {name: quick}
subsystems: [{name: S, type: T}]
telemetry:
  - {kind: position, frame: site, rate: 10, stale_after_ms: 1500}
  - {kind: agent, rate: 2}
"""


def test_declared_bound_reaches_the_cpp_tables_only_where_declared(tmp_path):
    (tmp_path / "a.yaml").write_text(DESCRIPTOR)
    sink = DiagnosticSink()
    loaded = load_asset(str(tmp_path / "a.yaml"), sink, RAPID)
    assert not [d for d in sink.diagnostics if d.severity.name == "ERROR"], sink.diagnostics
    lines = cpp_tables(loaded, {})
    starts = [i for i, ln in enumerate(lines) if ln.strip() == "::rapid_runtime::TelemetrySpec{"]
    assert len(starts) == 2
    position = lines[starts[0]:starts[1]]
    agent = lines[starts[1]:]
    assert '"position",' in position[1] and '"agent",' in agent[1]
    assert position[-1].strip().endswith(", /* stale_after_ms */ 1500.0},")
    assert not any("stale_after_ms" in ln for ln in agent)
