"""The Rust runtime's texts (runtime/rust/rapid_runtime/src/texts.rs) are generated from
runtime/spec/texts.yaml with the Python and C++ runtimes' (rapidgen.protocol_texts; fresh:
tests/runtime/test_texts.py), and the Rust runtime writes every text it may write through
them, none spelled out again."""
from __future__ import annotations

import re
from pathlib import Path

from rapidgen import protocol_texts as PT

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "runtime" / "rust" / "rapid_runtime" / "src"
# What the Rust runtime does not write yet: stale telemetry belongs to its DDS layer, still to
# come (docs/rust-backend.md). When it comes, this set shrinks.
NOT_YET = {"source_silent", "source_back"}


def test_texts_rs_is_the_generated_one():
    assert PT.RUST_OUT.read_text(encoding="utf-8") == PT.rust_source(PT.load_table())


def test_the_rust_runtime_writes_its_texts_through_texts_rs():
    code = "\n".join(p.read_text(encoding="utf-8") for p in sorted(SRC.rglob("*.rs")) if p.name != "texts.rs")
    table = PT.load_table()
    missing = [t.key for t in table if t.only is None and not re.search(rf"\btexts::{t.name}\b", code)]
    assert set(missing) == NOT_YET, f"texts the Rust runtime never writes through texts.rs: {missing}"
    # (doc comments and tests may quote a text; code that writes one must not spell it out)
    written = "\n".join(line.split("//")[0] for line in code.splitlines() if "assert" not in line)
    copied = [t.key for t in table if t.constant and " " in t.template and f'"{t.template}"' in written]
    assert not copied, f"texts spelled out again in the Rust runtime: {copied}"
