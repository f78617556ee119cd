"""`rapidgen conform` against the C++ bridges `rapidgen generate --lang cpp` writes: every
seed's (and a hostile descriptor's), built as their generated CMakeLists say on the C++
runtime (runtime/cpp) with -Wall -Wextra -Werror (tests/cpp_runtime/build.py, one build
per session shared with tests/cpp_runtime), run with --simulate on loopback (their built-in
Fast DDS profiles: rapid_local) and judged by the runner on cyclonedds. Nothing in these
bridges is written by hand: handlers.cpp stays as generated (--simulate replaces it).

Every check passes or does not apply (UNSUPPORTED: the descriptor has no queue, no access
control, no commands, no other telemetry); K10, which has everything, passes all.
Domains 40-45 (the seeds) and 47 (the hostile one)."""
from __future__ import annotations

import json
import subprocess
import sys
import time

import pytest

from tests.conformance.harness import conform, outcomes
from tests.cpp_runtime import build as B
from tests.runtime.live import SEEDS, env_for, python_dir

pytest.importorskip("cyclonedds")
DOMAINS = {**{seed: 40 + i for i, seed in enumerate(SEEDS)}, B.HOSTILE: 47}


@pytest.fixture(scope="module")
def bridges(tmp_path_factory) -> dict:
    return B.seed_bridges(tmp_path_factory)


def _conform_hostile(tmp_path_factory, out) -> dict:
    """The CLI on the hostile descriptor (harness.conform knows the seeds only)."""
    report = out / "hostile.json"
    t0 = time.monotonic()
    res = subprocess.run([sys.executable, "-m", "rapidgen", "conform", str(B.descriptor(tmp_path_factory, B.HOSTILE)),
                          "--domain", str(DOMAINS[B.HOSTILE]), "--json", str(report)], cwd=B.ROOT,
                         env=env_for(python_dir("k10"), SEEDS["k10"]), capture_output=True, text=True, timeout=240)
    return {"code": res.returncode, "stdout": res.stdout, "stderr": res.stderr,
            "report": json.loads(report.read_text()) if report.exists() else None, "seconds": time.monotonic() - t0}


@pytest.mark.parametrize("seed", list(DOMAINS))
def test_generated_cpp_bridge_passes_rapidgen_conform(seed, bridges, tmp_path, tmp_path_factory):
    if seed not in bridges:
        pytest.skip(f"{seed} not among RAPIDGEN_CPP_SEEDS")
    domain = DOMAINS[seed]
    proc = subprocess.Popen([str(bridges[seed]), "--simulate", "--domain", str(domain), "--seconds", "180"],
                            env=B.dds_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        ready = proc.stdout.readline()
        assert ready.startswith("bridge ready: ") and ready.rstrip().endswith(", simulated"), ready
        run = _conform_hostile(tmp_path_factory, tmp_path) if seed == B.HOSTILE else conform(seed, domain, tmp_path)
        alive = proc.poll() is None
    finally:
        proc.terminate()
        out, err = proc.communicate(timeout=30)
    assert run["report"] is not None, run["stderr"][-3000:]
    got = outcomes(run["report"])
    passed = sum(o == "PASS" for o in got.values())
    print(f"C++ bridge {seed}: {passed} of {len(got)} checks pass, "
          f"{sum(o == 'UNSUPPORTED' for o in got.values())} do not apply, in {run['report']['seconds']:.1f} s")
    bad = {c["id"]: (c["level"], c["outcome"], c["message"][:300]) for c in run["report"]["checks"]
           if c["outcome"] not in ("PASS", "UNSUPPORTED")}
    assert not bad and run["code"] == 0, (bad, run["stdout"][-3000:], err[-2000:])
    if seed in ("k10", B.HOSTILE):  # queue, access control, every kind of telemetry: nothing may be skipped
        assert passed == len(got), {c: o for c, o in got.items() if o != "PASS"}
    assert alive, err[-2000:]
    assert proc.returncode == 0 and "bridge stopped" in out and "not sent" not in err, (proc.returncode, out, err[-2000:])
