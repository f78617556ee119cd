"""The generated Rust codec against the golden vectors, and under random and truncated bytes."""
from __future__ import annotations

import json
import subprocess

from rapidgen.backends.python.asset_tables import tables as tables_of
from tests.rust.conftest import ROOT, VECTORS, vector_lines


def test_every_golden_vector_decodes_and_reencodes_byte_identically(rust_build):
    lines = vector_lines()
    assert len(lines) == 264
    res = subprocess.run([str(rust_build / "vectors")], input="\n".join(lines), capture_output=True,
                         text=True, timeout=120)
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-2000:]
    assert res.stdout.strip().splitlines()[-1] == "ok 264"


def test_random_and_truncated_bytes_never_panic_nor_overallocate(rust_build):
    res = subprocess.run([str(rust_build / "fuzz"), "300"], input="\n".join(vector_lines()),
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-4000:]
    words = res.stdout.split()
    counts = dict(zip(words[::2], map(int, words[1::2])))
    assert counts["seeds"] == 2 * 264
    # both outcomes occur: the loop really exercised the decoders' refusals and successes
    assert counts["decoded"] > 2 * 264 and counts["refused"] > 10_000
    assert counts["over"] == 0
    assert counts["differ"] == 0  # decode_into a kept value: deserialize's outcome, every input


def test_decode_into_and_serialize_into_reuse_kept_values_without_allocating(rust_build):
    res = subprocess.run([str(rust_build / "reuse")], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-4000:]
    assert res.stdout.split() == ["ok"]


def _filled(default: object, given: object) -> object:
    """`given` (members may be left out) over the default value of its type."""
    if isinstance(default, dict) and isinstance(given, dict) and "discriminator" not in given:
        return {k: _filled(v, given[k]) if k in given else v for k, v in default.items()}
    return given


def test_asset_configs_encode_as_the_reference_encoder_does(rust_build):
    from rapidgen.asset.load import load_asset
    from rapidgen.cdr import Codec
    from rapidgen.diagnostics import DiagnosticSink

    loaded = load_asset(str(ROOT / "specs" / "assets" / "k10.yaml"), DiagnosticSink())
    assert loaded is not None
    defaults = {v["type"]: v["value"] for v in json.loads(VECTORS.read_text(encoding="utf-8"))["vectors"]
                if v["variant"] == "min"}
    codec = Codec(loaded.model)
    expected = {topic: codec.encode(ty, _filled(defaults[ty], value)).hex()
                for topic, (ty, value) in loaded.configs.items()}
    res = subprocess.run([str(rust_build / "configs")], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stderr
    *lines, sizes = res.stdout.splitlines()
    assert dict(line.split() for line in lines) == expected and len(expected) >= 3
    tables = tables_of(loaded)
    assert sizes.split() == ["commands", str(sum(len(c) for c in tables["COMMANDS"].values())),
                             "topics", str(len(tables["PUBLICATIONS"]))]
