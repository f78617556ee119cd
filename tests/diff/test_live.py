"""LIVE: the diff's wire verdict agrees with Cyclone DDS.

For a sample of rule pairs (some WIRE-safe, some WIRE-breaking), a reader built from OLD's
generated Python bindings and a writer built from NEW's run in two processes on loopback
(tests/interop/cyclonedds-loopback.xml, one DDS domain per pair, all pairs at once): they
must match and deliver a sample exactly when `rapidgen diff` reports no WIRE change.
Pairs where Cyclone is known to be more lenient than XTypes 1.3 (key changes, @mutable id
changes, shrunk bounds: docs/diff.md) are not in the sample.
"""
from __future__ import annotations

import pytest

from tests.diff.conftest import diff_paths, idl_pair
from tests.diff.test_rules import IDL_PAIRS, SAFE_IDL

pytest.importorskip("cyclonedds")

SAMPLE = {
    "safe: append to @appendable": SAFE_IDL["append to @appendable"],
    "safe: grow a string bound": SAFE_IDL["grow a string bound"],
    "safe: grow a sequence bound": SAFE_IDL["grow a sequence bound"],
    "source: typedef spelt out": IDL_PAIRS["SRC-TYPE-01"],
    "source: trailing member removed (@appendable)": IDL_PAIRS["SRC-MEMBER-01"],
    "wire: member added to @final": IDL_PAIRS["WIRE-MEMBER-02"],
    "wire: inserted in @appendable": IDL_PAIRS["WIRE-MEMBER-03"],
    "wire: members reordered": IDL_PAIRS["WIRE-MEMBER-04"],
    "wire: member renamed": IDL_PAIRS["WIRE-MEMBER-05"],
    "wire: member widened": IDL_PAIRS["WIRE-MEMBER-06"],
}
FIRST_DOMAIN = 71  # 71..80: apart from the other live tests (43, ...)


def test_wire_verdict_agrees_with_cyclone(tmp_path):
    from tests.diff.live import exchange

    verdicts, pairs = {}, []
    for i, (name, (old, new)) in enumerate(SAMPLE.items()):
        found = diff_paths(*idl_pair(tmp_path / f"d{i}", old, new))
        verdicts[name] = not any(f.rule.category == "WIRE" for f in found)
        pairs.append((f"module t {{\n{old}\n}};\n", f"module t {{\n{new}\n}};\n", "t::S"))
    assert sum(verdicts.values()) == 5, verdicts  # the sample holds both kinds
    results = exchange(str(tmp_path / "live"), pairs, FIRST_DOMAIN)
    disagree = {name: (verdicts[name], r) for name, r in zip(SAMPLE, results)
                if (r["matched"] and r["received"]) != verdicts[name]}
    assert not disagree, f"diff's WIRE-safe verdict vs Cyclone (matched, received): {disagree}"
