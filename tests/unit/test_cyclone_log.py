"""rapidgen's live tools leave Cyclone's warnings out (rapidgen/live/cyclone_log.py: a C++
bridge's retired acks gave one 'keyhash is MD5' line each, thousands on a busy bridge) and
keep its errors; RAPIDGEN_DDS_WARNINGS=1 shows them. Checked on the library's own log mask,
in a child process (the mask is process-wide)."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

PROBE = """
import ctypes, json
from cyclonedds.internal import load_cyclonedds
from rapidgen.live.cyclone_log import quiet_warnings
lib = load_cyclonedds()
lib.dds_get_log_mask.restype = ctypes.c_uint32
before = lib.dds_get_log_mask()
print(json.dumps([before, quiet_warnings(), lib.dds_get_log_mask()]))
"""


@pytest.mark.parametrize("show, quiet", [(None, True), ("1", False), ("0", True)])
def test_warnings_left_out_unless_asked_for(show, quiet):
    pytest.importorskip("cyclonedds")
    env = {k: v for k, v in os.environ.items() if k != "RAPIDGEN_DDS_WARNINGS"}
    if show is not None:
        env["RAPIDGEN_DDS_WARNINGS"] = show
    res = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=env, timeout=60)
    assert res.returncode == 0, res.stderr
    before, said, after = json.loads(res.stdout)
    assert before == 7  # Cyclone's default: fatal, error, warning
    assert said is quiet
    assert after == (3 if quiet else 7)  # errors (2) and fatal (1) always shown
