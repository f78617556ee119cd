"""The Rust asset runtime's core (runtime/rust/rapid_runtime, std only, no DDS) replays the
protocol specification (runtime/spec/cases) as the Python and C++ runtimes do: the cases as
`rapidgen.protocol_cases` writes them for every driver, the seeds' tables from the Python
runtime's (rapidgen.protocol_cases.seed_tables) as JSON, `cargo test --release` (the crate's
unit tests, then tests/spec_cases.rs, which names each failing case by file:line). The only
registry crate is serde_json (the driver's), at the version Cargo.lock pins."""
from __future__ import annotations

import json
import os
import re
import subprocess
import time
from pathlib import Path

from rapidgen.protocol_cases import SEEDS, load_cases, seed_tables
from tests.rust.conftest import cargo

ROOT = Path(__file__).resolve().parents[2]
CRATE = ROOT / "runtime" / "rust" / "rapid_runtime"


def tables_json(seed: str) -> dict:
    """The seed's tables (rapid_runtime.tables.Tables) as plain data for the Rust driver."""
    t = seed_tables(seed)
    types = []
    for type_name in dict.fromkeys(t.subsystems.values()):
        commands = [{"name": e.name, "abortable": e.abortable, "suspendable": e.suspendable, "standard": e.standard,
                     "description": e.description, "stop_timeout_ms": e.stop_timeout_ms or 0,
                     "params": [{"name": p.name, "type": p.type, "unit": p.unit or "", "min": p.min, "max": p.max,
                                 "allowed": list(p.allowed)} for p in e.params]}
                    for e in t.commands_of_type(type_name).values()]
        types.append({"name": type_name, "commands": commands})
    access = None if t.access is None else {
        "default": t.access.default, "rules": [{"source": r.source, "allow": list(r.allow)} for r in t.access.rules]}
    return {"name": t.name, "kind": t.kind, "domain": t.domain, "partition": t.partition,
            "subsystems": [{"name": n, "type": ty} for n, ty in t.subsystems.items()], "types": types,
            "access": access}


def test_rust_runtime_replays_every_spec_case(tmp_path, rust_target):
    cases = load_cases()
    (tmp_path / "cases.json").write_text(json.dumps({"cases": cases}), encoding="utf-8")
    (tmp_path / "tables.json").write_text(json.dumps({seed: tables_json(seed) for seed in SEEDS}), encoding="utf-8")
    env = dict(os.environ, CARGO_TARGET_DIR=str(rust_target), CARGO_TERM_COLOR="never",
               RAPID_SPEC_CASES=str(tmp_path / "cases.json"), RAPID_SPEC_TABLES=str(tmp_path / "tables.json"))
    env.pop("RAPID_SPEC_ONLY", None)
    start = time.monotonic()
    # stdin closed: cargo probes `rustc -` with the inherited stdin
    res = subprocess.run([cargo(), "test", "--release", "--locked", "--", "--nocapture", "--test-threads=1"],
                         cwd=CRATE, capture_output=True, text=True, timeout=1200, env=env, stdin=subprocess.DEVNULL)
    print(f"\nrust runtime: cargo test --release (build and run) took {time.monotonic() - start:.1f} s")
    failing = [line for line in res.stdout.splitlines() if line.startswith("FAIL ")]
    assert res.returncode == 0 and not failing, "\n".join(failing) + "\n" + res.stdout[-4000:] + res.stderr[-4000:]
    summary = re.search(r"spec cases: (\d+) of (\d+) passed", res.stdout)
    assert summary, res.stdout[-3000:]
    assert int(summary.group(1)) == int(summary.group(2)) == len(cases), summary.group(0)
