"""Golden snapshots of `rapidgen ir` for representative inputs.

Each case folder under ir/ holds `args` (the command-line arguments, run from the case
folder), the inputs, and `expected.json`. `pytest --update-golden` rewrites expectations.
"""
import difflib
from pathlib import Path

import pytest

from tests.helpers import rapidgen

CASES = sorted(p for p in (Path(__file__).parent / "ir").iterdir() if (p / "args").is_file())


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_ir_snapshot(case, monkeypatch, update_golden):
    monkeypatch.chdir(case)
    res = rapidgen("ir", *(case / "args").read_text().split())
    assert res.code == 0, res.err
    expected_path = case / "expected.json"
    if update_golden:
        expected_path.write_text(res.out)
    assert expected_path.exists(), f"{expected_path} is missing: run pytest --update-golden and review it"
    expected = expected_path.read_text()
    if res.out != expected:
        diff = "".join(difflib.unified_diff(expected.splitlines(True), res.out.splitlines(True),
                                            "expected.json", "actual"))
        pytest.fail(f"IR of {case.name} differs from the golden file:\n{diff}")


def test_ir_is_deterministic(monkeypatch):
    case = next(c for c in CASES if c.name == "rapid_dialect")
    monkeypatch.chdir(case)
    args = (case / "args").read_text().split()
    assert rapidgen("ir", *args).out == rapidgen("ir", *args).out
