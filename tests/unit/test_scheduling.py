"""scripts/test hands the xdist workers the longest units of work first, by a measured run
(tests/durations.json): every unit it names must still exist, or a renamed slow file would
silently go back to the end of the queue."""
from __future__ import annotations

from pathlib import Path

from tests.conftest import _measured_seconds, _xdist_scope

ROOT = Path(__file__).resolve().parents[2]


def test_every_measured_unit_exists_and_is_a_unit_the_workers_take():
    seconds = _measured_seconds()
    assert len(seconds) >= 20
    for unit, wall in seconds.items():
        assert (ROOT / unit).exists(), f"tests/durations.json names {unit}, which is gone: refresh it"
        assert _xdist_scope(f"{unit}::test_x") == unit and wall > 0


def test_the_slow_tiers_are_measured():
    """The builds and campaigns: without a figure one would start last."""
    seconds = _measured_seconds()
    for unit in ("tests/conformance/test_cpp_asset.py", "tests/rust", "tests/rust_runtime/test_dds_bridge.py",
                 "tests/conformance/test_conformance.py", "tests/cpp_client/test_broken.py"):
        assert seconds.get(unit, 0) >= 100, unit
