"""The Python bridge secured (issue 35 items 1 and 7; docs/secure.md): K10's generated Python
bridge with RAPID_SECURITY_KEYSTORE, on the Cyclone DDS with DDS Security that
scripts/setup.sh builds, in a private network namespace (only lo). Its ground tools are the
C++ ones (tests/secure/cpp/ground.cpp, Fast DDS 2.9's plugins) and `rapidgen conform`.

- RapidWorkbench as itself: N of N run.
- ScienceBackroom's own valid certificate, granted to command K10Red, sending as
  RapidWorkbench: 0 of N, each answered "cmdSrc 'RapidWorkbench' is not the writer's
  identity 'ScienceBackroom'", and the bridge logs each.
- `rapidgen conform --enclave RapidWorkbench` afterwards: every required check passes."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.secure.conftest import DOMAIN, ROOT, run_scenario

N = 3
WAIT_S = "40"  # each tool ends once its N commands are answered; a loaded machine's margin


@pytest.fixture(scope="module")
def k10_python(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("k10py")
    subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(ROOT / "specs" / "assets" / "k10.yaml"),
                    "--lang", "python", "-o", str(out)], check=True, capture_output=True, cwd=ROOT, timeout=300)
    return out / "python"


def _ground(programs: dict, enclave: Path, source: str, prefix: str) -> dict:
    return {"argv": [str(programs["ground"]), "command", str(programs["profiles"]), str(DOMAIN), "K10Red", source,
                     prefix, str(N), WAIT_S],
            "env": {"RAPID_SECURITY_KEYSTORE": str(enclave.parents[1]), "RAPID_SECURITY_ENCLAVE": str(enclave)}}


@pytest.fixture(scope="module")
def secured(keystores, programs, k10_python, tmp_path_factory) -> dict:
    ks = keystores["main"]
    enclaves = ks / "enclaves"
    return run_scenario(tmp_path_factory.mktemp("python_bridge"), {
        "bridge": [sys.executable, "-m", "rapid_k10red.bridge", "--simulate", "--domain", str(DOMAIN),
                   "--no-journal", "--seconds", "150"],
        "bridge_env": {"RAPID_SECURITY_KEYSTORE": str(ks), "PYTHONPATH": str(k10_python)}, "ready_s": 60,
        "cases": {"itself": _ground(programs, enclaves / "RapidWorkbench", "RapidWorkbench", "itself"),
                  "spoof": _ground(programs, enclaves / "ScienceBackroom", "RapidWorkbench", "spoofed")},
        "watch": {"argv": [sys.executable, "-m", "rapidgen", "conform", str(ROOT / "specs" / "assets" / "k10.yaml"),
                           "--domain", str(DOMAIN), "--timeout", "10", "--enclave", str(enclaves / "RapidWorkbench")],
                  "env": {}}})


def test_the_operator_runs_n_of_n_on_the_secured_python_bridge(secured):
    assert secured["bridge_ready"], secured["bridge"]
    case = secured["cases"]["itself"]
    assert f"completed: {N} of {N}" in case["stdout"], case


def test_a_valid_certificate_cannot_send_as_another_source(secured):
    case = secured["cases"]["spoof"]
    assert "completed: 0 of" in case["stdout"], case
    why = "cmdSrc 'RapidWorkbench' is not the writer's identity 'ScienceBackroom'"
    refused = [line for line in case["stdout"].splitlines() if line.startswith("failed spoofed-") and why in line]
    assert len(refused) == N + 1, case  # each, and its control command, answered with the reason


def test_conform_with_an_enclave_passes_against_the_secured_python_bridge(secured):
    case = secured["watch"]
    assert case["rc"] == 0 and "every required check passed" in case["stdout"], case
