"""The C++ bridge's command intake fed malformed and random Commands over DDS under
ASan/UBSan (K10's bridge built with the runtime's core and the types' codec sanitized:
build.py client_programs): tests/cpp_client/fuzz.py writes RAPIDGEN_FUZZ_COUNT samples
(default 1500) as raw CDR through cyclonedds. The bridge never crashes (no sanitizer
report, clean exit), answers every well-formed command and still completes Admin/echo.
Domain 24."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from tests.cpp_runtime import build as B
from tests.runtime.live import SEEDS, env_for, python_dir

pytest.importorskip("cyclonedds")
DOMAIN = 24
COUNT = int(os.environ.get("RAPIDGEN_FUZZ_COUNT", "1500"))


def test_intake_survives_malformed_commands_under_sanitizers(programs):
    # new_delete_type_mismatch=0: Debian's Fast DDS 2.9 deletes its StatisticsReaderImpl as an
    # RTPSReader when a participant is deleted (its bug, in its library, at shutdown)
    env = dict(B.dds_env(), ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:new_delete_type_mismatch=0",
               UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1")
    bridge = subprocess.Popen([str(programs["bridge_test"]), "--simulate", "--domain", str(DOMAIN), "--seconds", "900"],
                              env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert bridge.stdout.readline().startswith("bridge ready: asset K10Red")
        res = subprocess.run([sys.executable, "-m", "tests.cpp_client.fuzz", str(DOMAIN), str(COUNT), "21"],
                             cwd=B.ROOT, env=env_for(python_dir("k10"), SEEDS["k10"]), capture_output=True,
                             text=True, timeout=900)
        alive = bridge.poll() is None
    finally:
        if bridge.poll() is None:
            bridge.terminate()
        out, err = bridge.communicate(timeout=60)
    assert res.returncode == 0, res.stderr[-3000:]
    got = json.loads(res.stdout.splitlines()[-1])
    print(f"fuzz: {got}")
    assert "AddressSanitizer" not in err and "runtime error:" not in err, err[-4000:]
    assert alive and bridge.returncode == 0 and "bridge stopped" in out, (bridge.returncode, err[-3000:])
    assert got["written"] >= COUNT // 3 and got["written"] - got["well_formed"] >= COUNT // 10, got  # both kinds sent
    assert got["well_formed"] > 0 and got["answered"] == got["well_formed"], got
    assert got["alive"], got
