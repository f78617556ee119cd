"""K10's generated C++ bridge writes acks through writer generations
(runtime/cpp/dds/include/rapid_runtime/dds/ack_writers.hpp, runtime/cpp/README.md): commands
dealt to DataWriters of max(256, window / 4) commands, the next made half a generation
early, an old one deleted whole once every command it took is retired, no instance
unregistered (Fast DDS 2.9 freed those one linear search at a time on the receive thread:
issue 40). Driven by a Python commander (cyclonedds), the ground processes of the Rust
bridge's tests (tests/rust_runtime/ground.py). Domain 54."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from tests.cpp_runtime import build as B

pytest.importorskip("cyclonedds")

DOMAIN = 54
PYDIR = B.ROOT / "generated" / "k10" / "python"
LOCAL = B.ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"


def _ground(check: str, n: int) -> dict:
    res = subprocess.run([sys.executable, "-m", "tests.rust_runtime.ground", check, str(PYDIR), "rapid_k10red",
                          str(DOMAIN), str(n)], cwd=B.ROOT, capture_output=True, text=True, timeout=240,
                         env=dict(os.environ, CYCLONEDDS_URI=f"file://{LOCAL}", PYTHONPATH=f"{PYDIR}{os.pathsep}{B.ROOT}"))
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
    return json.loads(res.stdout.splitlines()[-1])


def test_old_ack_writer_generations_are_deleted_and_late_joiners_get_the_acks(programs):
    """With --command-window 16 (generations of 256), after 700 noOps: all answered, two ack
    writers alive (the current generation's, 512-767, and the next, made early at 640), the
    first two generations (every command retired) deleted; one writer served them all
    before. Then 20 more noOps and an ack reader joining late: it gets each one's final ack
    (per-command instances of the live generation, kept transient-local)."""
    proc = subprocess.Popen([str(programs["k10"]), "--simulate", "--domain", str(DOMAIN), "--command-window", "16",
                             "--seconds", "240"], env=B.dds_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        assert proc.stdout.readline().startswith("bridge ready: asset K10Red")
        writers = _ground("ack-writers", 700)
        late = _ground("late-acks", 20)
        alive = proc.poll() is None
    finally:
        proc.terminate()
        _, err = proc.communicate(timeout=30)
    assert alive, err[-3000:]
    assert writers == {"answered": 700, "ack_writers": 2}, (writers, err[-3000:])
    assert len(late["sent"]) == 20
    missing = [cid for cid, last in late["last"].items() if not (last or "").startswith("ACK_COMPLETED ")]
    assert not missing, (missing, late)
    assert "not deleted" not in err and "not written" not in err, err[-3000:]
