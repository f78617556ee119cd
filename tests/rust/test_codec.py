"""The generated Rust codec against the golden vectors, and under random and truncated bytes."""
from __future__ import annotations

import subprocess

from tests.rust.conftest import vector_lines


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
