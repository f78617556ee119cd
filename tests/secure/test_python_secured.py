"""The Python side secured (issue 24): the Python bridge (rapid_runtime) and `rapidgen
conform` on a Cyclone DDS 11.0.1 built with DDS Security, with the keystore's
cyclonedds-security.xml, in a private network namespace. The PyPI wheel is built without
DDS Security, so this needs tests/secure/cyclone_security.sh PREFIX (about 7 minutes) and
RAPIDGEN_CYCLONE_SECURITY=PREFIX; without it the tests are skipped, saying why.

An authorised runner (RapidWorkbench: commands and audits K10Red) judges the secured
bridge: every required check passes. An unsecured runner beside it finds no asset."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.secure.conftest import DOMAIN, ROOT, run_scenario

PREFIX = os.environ.get("RAPIDGEN_CYCLONE_SECURITY", "")
pytestmark = pytest.mark.skipif(
    not PREFIX, reason="needs a Cyclone DDS built with DDS Security: tests/secure/cyclone_security.sh PREFIX, "
    "then RAPIDGEN_CYCLONE_SECURITY=PREFIX (the cyclonedds wheel has no DDS Security)")


@pytest.fixture(scope="module")
def k10_python(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("k10py")
    subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(ROOT / "specs" / "assets" / "k10.yaml"),
                    "--lang", "python", "-o", str(out)], check=True, capture_output=True, cwd=ROOT, timeout=300)
    return out / "python"


def _env(uri_files: list[Path], **extra: str) -> dict:
    env = {"LD_LIBRARY_PATH": f"{PREFIX}/lib", "CYCLONEDDS_HOME": PREFIX,
           "CYCLONEDDS_URI": ",".join(f"file://{p}" for p in uri_files)}
    env.update(extra)
    return env


def test_conformance_passes_against_the_secured_python_bridge(keystores, k10_python, tmp_path):
    python = f"{PREFIX}/venv/bin/python"
    local = k10_python / "rapid_k10red" / "qos_files" / "cyclonedds" / "local.xml"
    enclaves = keystores["main"] / "enclaves"

    def conform(enclave: str | None) -> dict:
        files = [local] + ([enclaves / enclave / "cyclonedds-security.xml"] if enclave else [])
        return {"argv": [python, "-m", "rapidgen", "conform", str(ROOT / "specs" / "assets" / "k10.yaml"),
                         "--domain", str(DOMAIN), "--timeout", "10"], "env": _env(files)}
    result = run_scenario(tmp_path, {
        "bridge": [python, "-m", "rapid_k10red.bridge", "--simulate", "--domain", str(DOMAIN)],
        "bridge_env": _env([local, enclaves / "K10Red" / "cyclonedds-security.xml"], PYTHONPATH=str(k10_python)),
        "ready_s": 60, "cases": {"authorised": conform("RapidWorkbench"), "no_certificate": conform(None)}})
    assert result["bridge_ready"], result["bridge"]
    ok = result["cases"]["authorised"]
    assert ok["rc"] == 0 and "every required check passed" in ok["stdout"], ok
    stranger = result["cases"]["no_certificate"]
    assert stranger["rc"] == 1 and "no participant with K10Red's topics" in stranger["stderr"], stranger
