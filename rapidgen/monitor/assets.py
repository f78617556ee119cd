"""The types and hints the monitor reads with: the RAPID base types (shipped IDL, through a
minimal descriptor, as `rapidgen spy` does) and, per --asset, its generated bindings
(extension types) and its descriptor's hints (units, ranges, thresholds, sources)."""
from __future__ import annotations

import os
import tempfile

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.monitor.hints import Hints

# The base types, with one subsystem so that the package's QoS map has the command topics
# (the monitor writes rapid_command with its profile's QoS).
BASE_DESCRIPTOR = """version: 1
asset: {name: RapidMonitor, kind: other}
dds: {domain: 0}
subsystems: [{name: Admin}]
telemetry: []
"""


def load(files: list[str], sink: DiagnosticSink) -> tuple[list, Hints] | None:
    """([each asset's bindings..., the base bindings], hints), or None after diagnostics."""
    from rapidgen.asset import load_asset
    from rapidgen.live.bindings import load_bindings
    with tempfile.TemporaryDirectory(prefix="rapidgen-monitor-") as tmp:
        path = os.path.join(tmp, "rapid-monitor.yaml")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(BASE_DESCRIPTOR)
        base = load_bindings(path, sink, prefix="rapidmonitor_base")
    if base is None:
        return None
    assets, pairs = [], []
    for i, f in enumerate(files):
        b = load_bindings(f, sink, prefix=f"rapidmonitor{i}")
        if b is None:
            return None
        loaded = load_asset(f, DiagnosticSink())  # read again for what the tables leave out: thresholds
        assets.append(b)
        pairs.append((b.tables, loaded.spec if loaded is not None else None))
    return assets + [base], Hints.of(pairs)
