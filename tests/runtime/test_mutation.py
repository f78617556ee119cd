"""bench/mutation.py, short (the full campaign: `python bench/mutation.py`, figures in
bench/README.md): three mutants of one function whose behaviour the protocol fixes
(Pending.insert_after: where QUEUE_INSERT lands), judged by the spec cases and, for those
the cases let live, by rapidgen conform against K10's bridge on the mutant (domain 8). The
unmutated runtime passes both oracles first (the script exits 1 otherwise), and a
misplaced insert is killed: an oracle that passes everything would kill none."""
from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.runtime.live import ROOT

pytest.importorskip("mutmut")
pytest.importorskip("cyclonedds")
DOMAIN = 8


def test_insert_after_mutants_are_killed(tmp_path):
    out = tmp_path / "verdicts.json"
    res = subprocess.run([sys.executable, "bench/mutation.py", "--function", "insert_after", "--sample", "3", "--oracle", "both",
                          "--domain", str(DOMAIN), "--json", str(out)], cwd=ROOT, capture_output=True, text=True,
                         timeout=900)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    got = json.loads(out.read_text())
    verdicts = got["verdicts"]
    assert verdicts and all(v["mutant"].startswith("rapid_runtime.cmdqueue.") for v in verdicts)
    killed = [v for v in verdicts if v["killed"]]
    assert killed, res.stdout[-3000:]
    assert all(v["by"].startswith(("spec:", "conform:")) for v in killed)
    assert "score:" in res.stdout and "95% CI" in res.stdout
