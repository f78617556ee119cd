"""The C++ asset runtime (runtime/cpp): built with -Wall -Wextra -Werror (conftest.py, once
per session), its GoogleTest suite of the protocol logic run without DDS, and K10's bridge
assembled on it (hand-written tables, generated types) judged by `rapidgen conform`."""
from __future__ import annotations

import os
import re
import subprocess

import pytest

from tests.cpp_runtime.conftest import ROOT


def test_logic_suite_passes(runtime_build):
    res = subprocess.run([str(runtime_build / "logic"), "--gtest_brief=1"], capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stdout[-6000:] + res.stderr[-3000:]
    ran = re.search(r"\[==========\] (\d+) tests", res.stdout)
    assert ran and int(ran.group(1)) >= 30, res.stdout[-2000:]


def test_logic_suite_is_clean_under_thread_sanitizer(logic_under_tsan):
    res = subprocess.run([str(logic_under_tsan), "--gtest_brief=1"], capture_output=True, text=True, timeout=600,
                         env=dict(os.environ, TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"))
    assert res.returncode == 0 and "ThreadSanitizer" not in res.stderr, res.stdout[-3000:] + res.stderr[-6000:]


# ---- K10's bridge on the C++ runtime against `rapidgen conform` ---------------------------------

DOMAIN = 43  # the C++ runtime's tests use domains 40-49
K10_PROFILES = ROOT / "generated" / "k10" / "qos" / "fastdds" / "rapid_qos_profiles.xml"


def test_k10_bridge_passes_rapidgen_conform(k10_bridge, tmp_path):
    """The runner (Python, Cyclone) judges the bridge (C++, Fast DDS) on loopback: every
    check passes, required and recommended (46 with K10's descriptor when written)."""
    pytest.importorskip("cyclonedds")
    from tests.conformance.harness import conform, outcomes
    env = {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}
    bridge = subprocess.Popen([str(k10_bridge), "--qos", str(K10_PROFILES), "--domain", str(DOMAIN), "--seconds",
                               "180"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        ready = bridge.stdout.readline()
        assert "bridge ready" in ready, ready
        run = conform("k10", DOMAIN, tmp_path)
        alive = bridge.poll() is None
    finally:
        bridge.terminate()
        out, err = bridge.communicate(timeout=30)
    assert run["report"] is not None, run["stderr"][-3000:]
    got = outcomes(run["report"])
    print(f"C++ runtime K10 bridge: {sum(o == 'PASS' for o in got.values())} of {len(got)} checks pass "
          f"in {run['report']['seconds']:.1f} s")
    failed = {c["id"]: (c["level"], c["outcome"], c["message"]) for c in run["report"]["checks"]
              if c["outcome"] != "PASS"}
    assert not failed and run["code"] == 0, (failed, run["stdout"][-3000:], err[-2000:])
    assert alive, err[-2000:]
    assert bridge.returncode == 0 and "bridge stopped" in out, (bridge.returncode, out, err[-2000:])
