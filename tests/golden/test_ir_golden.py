"""Golden snapshots of `rapidgen ir` for representative inputs.

Each case folder under ir/ holds `args` (the command-line arguments, run from the case
folder), the inputs, and `expected.json`. `pytest --update-golden` rewrites expectations.
"""
from pathlib import Path

import pytest

from tests.helpers import assert_golden, rapidgen

CASES = sorted(p for p in (Path(__file__).parent / "ir").iterdir() if (p / "args").is_file())


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_ir_snapshot(case, monkeypatch, update_golden):
    monkeypatch.chdir(case)
    res = rapidgen("ir", *(case / "args").read_text().split())
    assert res.code == 0, res.err
    assert_golden(case / "expected.json", res.out, update_golden, f"IR of {case.name}")


def test_ir_is_deterministic(monkeypatch):
    case = next(c for c in CASES if c.name == "rapid_dialect")
    monkeypatch.chdir(case)
    args = (case / "args").read_text().split()
    assert rapidgen("ir", *args).out == rapidgen("ir", *args).out
