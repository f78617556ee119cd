"""The Rust asset runtime's core (runtime/rust/rapid_runtime, std only, no DDS) replays the
protocol specification (runtime/spec/cases) as the Python and C++ runtimes do: the cases as
`rapidgen.protocol_cases` writes them for every driver, the seeds' tables from the Python
runtime's (rapidgen.protocol_cases.seed_tables) as JSON, `cargo test` (the crate's
unit tests, then tests/spec_cases.rs, which names each failing case by file:line), and the
restart journal read and written across the Python and Rust runtimes in the same run. The only
registry crate is serde_json (the driver's), at the version Cargo.lock pins."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import time
from pathlib import Path

from rapid_runtime.command import Cmd
from rapid_runtime.journal import Entry, Journal, Recovered, _line, _record, file_name
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


def _entries(rec: Recovered) -> dict:
    def as_json(e) -> dict:
        return {"id": e.cmd_id, "src": e.src_name, "asset": e.asset_name, "serial": e.serial, "state": e.state,
                "c": e.completion, "m": e.message}
    return {"unfinished": [as_json(e) for e in rec.unfinished], "finished": [as_json(e) for e in rec.finished],
            "last_serial": rec.last_serial, "crashed": rec.crashed}


def _python_journal_at_a_crash(folder: Path) -> None:
    """A journal as the Python runtime leaves it when its process dies (no stop record)."""
    j, _ = Journal.open(folder, "K10Red", 7, 8, print)
    assert j is not None
    j.start(3)

    def cmd(cid: str) -> Cmd:
        return Cmd(cid, "src", "PanCam", "x", src_name="Work bench \u00e9", asset_name="K10Red", serial=2)

    j.note(cmd("a"), "q")
    j.note(cmd("a"), "x")
    j.note(cmd("b"), "q")
    j.note(cmd("c"), "q")
    j.note(cmd("c"), "c", "ACK_COMPLETED_OK", 'done \u2713 "q" \\ \U0001F600\n\x7f')
    j.serial(11)
    j.sync()
    os.close(j.fd)


def test_rust_runtime_replays_every_spec_case(tmp_path, rust_target):
    cases = load_cases()
    interop = tmp_path / "journals"
    _python_journal_at_a_crash(interop / "from_python")
    shutil.copytree(interop / "from_python", interop / "python_copy")  # (recovering rewrites the file)
    _, python_recovered = Journal.open(interop / "python_copy", "K10Red", 7, 8, print)
    (tmp_path / "cases.json").write_text(json.dumps({"cases": cases}), encoding="utf-8")
    (tmp_path / "tables.json").write_text(json.dumps({seed: tables_json(seed) for seed in SEEDS}), encoding="utf-8")
    env = dict(os.environ, CARGO_TARGET_DIR=str(rust_target), CARGO_TERM_COLOR="never",
               RAPID_SPEC_CASES=str(tmp_path / "cases.json"), RAPID_SPEC_TABLES=str(tmp_path / "tables.json"),
               RAPID_JOURNAL_INTEROP=str(interop))
    env.pop("RAPID_SPEC_ONLY", None)
    start = time.monotonic()
    # stdin closed: cargo probes `rustc -` with the inherited stdin
    # the dev profile: 6 CPU-s to build against --release's 21, and the cases run in seconds either way
    res = subprocess.run([cargo(), "test", "--locked", "--", "--nocapture", "--test-threads=1"],
                         cwd=CRATE, capture_output=True, text=True, timeout=1200, env=env, stdin=subprocess.DEVNULL)
    print(f"\nrust runtime: cargo test (build and run) took {time.monotonic() - start:.1f} s")
    failing = [line for line in res.stdout.splitlines() if line.startswith("FAIL ")]
    assert res.returncode == 0 and not failing, "\n".join(failing) + "\n" + res.stdout[-4000:] + res.stderr[-4000:]
    summary = re.search(r"spec cases: (\d+) of (\d+) passed", res.stdout)
    assert summary, res.stdout[-3000:]
    assert int(summary.group(1)) == int(summary.group(2)) == len(cases), summary.group(0)
    assert "test journal_interop ... ok" in res.stdout, res.stdout[-3000:]

    # the Python runtime's journal, recovered by the Rust runtime: what Python's own recovery gives
    assert python_recovered.crashed and len(python_recovered.unfinished) == 2
    assert json.loads((interop / "rust_recovered.json").read_text()) == _entries(python_recovered)
    # the Rust runtime's journal at a crash: its lines byte for byte as the Python runtime writes
    # the same records (key order, escapes, CRC), and recovered by the Python runtime
    lines = (interop / "from_rust" / file_name("K10Red", 7)).read_bytes().splitlines(keepends=True)
    assert len(lines) == 7, lines
    for raw in lines:
        rec = json.loads(raw[9:])
        if rec["k"] in ("q", "x", "c"):  # (the Python runtime's own key order)
            rec = _record(Entry(rec["id"], rec["src"], rec["asset"], rec["serial"], rec["k"], rec.get("c", ""),
                                rec.get("m", "")))
        assert raw == _line(rec), raw
    logs: list[str] = []
    j, rust_recovered = Journal.open(interop / "from_rust", "K10Red", 7, 8, logs.append)
    assert j is not None and not logs, logs
    os.close(j.fd)
    got = _entries(rust_recovered)
    assert got["crashed"] and got["last_serial"] == 9
    assert [(e["id"], e["state"]) for e in got["unfinished"]] == [("a", "x"), ("b", "q")]
    assert got["finished"] == [{"id": "c", "src": "Work bench \u00e9", "asset": "K10Red", "serial": 2, "state": "c",
                                "c": "ACK_COMPLETED_OK", "m": 'done \u2713 "q" \\ \U0001F600\n\x7f'}]
