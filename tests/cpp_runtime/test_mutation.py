"""bench/mutation_cpp.py, short (the full campaign: `python bench/mutation_cpp.py`, figures in
bench/README.md): three mutants (universalmutator's operators) of a function whose
behaviour the protocol fixes, Pending::insert_after in runtime/cpp/src/pending.cpp (where
QUEUE_INSERT lands), judged by the spec cases replayed by the C++ driver and (with
RAPIDGEN_MUTATION_CPP=1), for those the cases let live, by rapidgen conform against K10's
C++ bridge built on the mutant (domain 59). The unmutated runtime passes the oracles first (the script exits 1 otherwise), and a
misplaced insert is killed: an oracle that passes everything would kill none. Everything is
built in the script's own temporary folder, runtime/cpp is only read.

In the default run the cases alone judge (the spec oracle: the script builds a runtime core
of its own and links the run's tables and cases' driver, --prebuilt: about 25 CPU-s);
RAPIDGEN_MUTATION_CPP=1 adds conform against a bridge built on each mutant (about 3 minutes on 2 cores)."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from tests.cpp_runtime import build as B

pytest.importorskip("universalmutator")
pytest.importorskip("cyclonedds")
DOMAIN = 59  # (Fast DDS: below 102)
ORACLE = "both" if os.environ.get("RAPIDGEN_MUTATION_CPP") == "1" else "spec"


def test_insert_after_mutants_are_killed(tmp_path, runtime_build):
    out = tmp_path / "verdicts.json"
    # (the run's tables and cases' driver linked, not compiled again: runtime_build, conftest.py)
    res = subprocess.run([sys.executable, "bench/mutation_cpp.py", "--where", "pending.cpp:insert_after", "--sample", "3",
                          "--oracle", ORACLE, "--domain", str(DOMAIN), "--jobs", B.JOBS, "--json", str(out),
                          "--prebuilt", str(runtime_build)],
                         cwd=B.ROOT, capture_output=True, text=True, timeout=1200, env=B.dds_env())
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    got = json.loads(out.read_text())
    verdicts = got["verdicts"]
    assert len(verdicts) == 3 and all(v["mutant"].startswith("pending.cpp:") for v in verdicts), verdicts
    killed = [v for v in verdicts if v["killed"]]
    assert killed, res.stdout[-3000:]
    assert all(v["by"].startswith(("spec:", "conform:")) for v in killed)
    assert "score:" in res.stdout and "95% CI" in res.stdout
