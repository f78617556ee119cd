"""The generated C++ codec against the golden vectors, and under random and truncated bytes."""
from __future__ import annotations

import subprocess

from tests.cpp.conftest import ROOT, vector_lines


def test_every_golden_vector_decodes_and_reencodes_byte_identically(cpp_build):
    lines = vector_lines()
    assert len(lines) == 264
    res = subprocess.run([str(cpp_build / "vectors")], input="\n".join(lines), capture_output=True,
                         text=True, timeout=120)
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-2000:]
    assert res.stdout.strip().splitlines()[-1] == "ok 264"


def test_random_and_truncated_bytes_never_crash_under_asan_ubsan(cpp_build):
    res = subprocess.run([str(cpp_build / "fuzz"), "300"], input="\n".join(vector_lines()),
                         capture_output=True, text=True, timeout=300,
                         env={"ASAN_OPTIONS": "detect_leaks=1:abort_on_error=1", "UBSAN_OPTIONS": "print_stacktrace=1"})
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-4000:]
    words = res.stdout.split()
    counts = dict(zip(words[::2], map(int, words[1::2])))
    assert counts["seeds"] == 2 * 264
    # both outcomes occur: the loop really exercised the decoders' refusals and successes
    assert counts["decoded"] > 264 and counts["refused"] > 10_000


def test_asset_configs_as_cpp_values_encode_like_the_reference_encoder(cpp_build):
    from rapidgen.asset.load import load_asset
    from rapidgen.cdr.codec import encode
    from rapidgen.diagnostics import DiagnosticSink

    loaded = load_asset(str(ROOT / "specs" / "assets" / "k10.yaml"), DiagnosticSink())
    # the header is the publisher's to fill in: all zero in both
    hdr = {"srcName": "", "assetName": "", "timeStamp": 0, "statusCode": 0, "serial": 0}
    want = {topic: encode(loaded.model, ty, {"hdr": hdr, **value}).hex() for topic, (ty, value) in loaded.configs.items()}
    assert len(want) == 3  # command dictionary, position, agent (GPS config is custom)
    res = subprocess.run([str(cpp_build / "configs")], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stderr
    lines = res.stdout.splitlines()
    assert lines[0] == "17 publications"
    assert dict(line.split() for line in lines[1:]) == want
