"""The Rust runtime's texts (runtime/rust/rapid_runtime/src/texts.rs, written by hand) say what
runtime/spec/texts.yaml says: every text (but those only the Python runtime writes) is there with
the table's words, as a constant or as a function taking the table's placeholders in order, and
nothing else is (the Python and C++ runtimes' are generated: rapidgen.protocol_texts)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]
TABLE = ROOT / "runtime" / "spec" / "texts.yaml"
RUST = ROOT / "runtime" / "rust" / "rapid_runtime" / "src" / "texts.rs"
TYPES = {"text": "&str", "count": "usize", "seconds": "f64"}


def expected(key: str, entry: dict) -> str:
    """The item texts.rs holds for one text of the table."""
    args = entry.get("args") or {}
    if not args:
        return f"pub const {key.upper()}: &str = {json.dumps(entry['text'], ensure_ascii=False)};"
    words = entry["text"]
    for name, kind in args.items():
        if kind == "seconds":  # one decimal, as Python's format(x, '.1f')
            words = words.replace("{" + name + "}", "{" + name + ":.1}")
    params = ", ".join(f"{name}: {TYPES[kind]}" for name, kind in args.items())
    return f"pub fn {key}({params}) -> String {{\n    format!({json.dumps(words, ensure_ascii=False)})\n}}"


def test_rust_texts_follow_the_table():
    table = yaml.safe_load(TABLE.read_text(encoding="utf-8"))["texts"]
    source = RUST.read_text(encoding="utf-8")
    wanted = {k: e for k, e in table.items() if e.get("only") != "python"}
    missing = [expected(k, e) for k, e in wanted.items() if expected(k, e) not in source]
    assert not missing, "texts.rs differs from runtime/spec/texts.yaml; expected:\n" + "\n".join(missing)
    names = set(re.findall(r"^pub (?:const ([A-Z0-9_]+)|fn ([a-z0-9_]+))", source, re.M))
    extra = {c or f for c, f in names} - {k.upper() if not (e.get("args") or {}) else k for k, e in wanted.items()}
    assert not extra, f"texts.rs holds texts the table does not: {sorted(extra)}"
