"""The README's main job, end to end: `bash scripts/demo` on its own DDS domain (loopback
only, the package's local transport) exits 0 having shown each step's result."""
from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_demo_runs_end_to_end():
    env = dict(os.environ, DEMO_DOMAIN="166", RAPIDGEN_SKIP_APT="1")
    res = subprocess.run(["bash", "scripts/demo"], cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)
    out = res.stdout
    assert res.returncode == 0, out[-3000:] + res.stderr[-3000:]
    assert "bridge ready: asset K10Red, domain 166" in out
    assert "rapid_command_config             rapid::CommandConfig   from K10Red: matches the descriptor" in out
    assert "COMPLETED OK  arrived at 2.00, 1.00" in out  # the valid command
    assert "error[RG1905]: pan: 4 not in [-3.05, 3.05]" in res.stderr  # the invalid one, refused
    assert "COMPLETED BAD_SYNTAX  argument 1 (pan)" in out  # ... and answered when sent anyway
    # (the DELETE is answered at once; the drive's own CANCELED follows when its handler stops)
    assert "COMPLETED OK  demo-long-drive cancel requested; handler has not stopped yet" in out \
        and "COMPLETED CANCELED" in out
    assert "watch: position from K10Red" in out and "watch: agent    from K10Red" in out
    # the conformance run: every check passes, recommended ones included (a newcomer sees no FAIL)
    assert re.search(r"^K10Red: (\d+) checks, \1 pass in [\d.]+ s; every required check passed$", out, re.M), out[-2000:]
    assert out.rstrip().endswith("bridge stopped\ndemo: ok")
