"""Negative descriptors: each tests/asset/negative/<case>.yaml has <case>.expected holding
what `rapidgen validate` prints on stderr (file:line:col, message, excerpt, hint) and
its exit status. `pytest --update-golden` rewrites the expectations; review the diff."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.helpers import assert_golden, rapidgen

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent / "negative"
CASES = sorted(p.stem for p in HERE.glob("*.yaml"))
LOCATED = re.compile(r"^tests/asset/negative/[\w.-]+\.yaml:\d+:\d+: (error|warning)\[RG1\d{3}\]: ")


def test_enough_cases():
    assert len(CASES) >= 30


@pytest.mark.parametrize("case", CASES)
def test_negative_case(case, update_golden, monkeypatch):
    monkeypatch.chdir(ROOT)
    res = rapidgen("validate", f"tests/asset/negative/{case}.yaml")
    got = res.err + f"exit: {res.code}\n"
    assert "Traceback" not in got and "internal error" not in got
    assert res.code == (0 if case.startswith("warn-") else 1)
    heads = [line for line in res.err.splitlines() if re.match(r"^\S+:\d+:\d+: ", line)]
    assert heads and all(LOCATED.match(h) for h in heads), res.err
    assert_golden(HERE / f"{case}.expected", got, update_golden, "diagnostics")
