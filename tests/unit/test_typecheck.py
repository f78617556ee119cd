"""The type-check tier: mypy over rapidgen/, the asset runtime and the conformance runner,
configured in pyproject.toml ([tool.mypy]: the files, the strictness, and the modules still
being written, whose errors are not reported yet). Any error fails this test with mypy's
own report."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]  # mypy is in the test extra (scripts/setup.sh installs it)


def test_mypy_finds_no_errors(tmp_path):
    # A fresh cache in the run's temporary folder: nothing stale, nothing left in the tree.
    res = subprocess.run([sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path / "mypy-cache"),
                          "--no-error-summary", "--hide-error-context"],
                         cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, f"mypy found errors:\n{res.stdout}{res.stderr}"
    assert res.stdout.strip() == "", res.stdout


def test_the_tier_would_catch_an_error(tmp_path):
    """The configuration really checks: a type error in a checked module is reported."""
    bad = tmp_path / "bad_module.py"
    bad.write_text("from rapidgen.model import ir\n\nx: int = ir.MEMBER_ID_MASK\ny: str = x\n", encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path / "mypy-cache"),
                          "--config-file", str(ROOT / "pyproject.toml"), str(bad)],
                         cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert res.returncode == 1 and 'Incompatible types in assignment (expression has type "int", variable ' \
        'has type "str")' in res.stdout, res.stdout + res.stderr
