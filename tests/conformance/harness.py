"""Running `rapidgen conform` against a bridge on loopback, each run on a DDS domain no
other run uses at the same time (200-232: no other test tier uses these)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir

DOMAIN_BASE = 200
RAPIDGEN = [sys.executable, "-m", "rapidgen"]
DESCRIPTORS = {a: ROOT / "specs" / "assets" / f"{a}.yaml" for a in SEEDS}


def conform(asset: str, domain: int, out: Path, *extra: str) -> dict:
    """Run the CLI; returns {code, stdout, stderr, report (JSON), junit (path), seconds}."""
    pydir = python_dir(asset)
    report, junit = out / f"{asset}-{domain}.json", out / f"{asset}-{domain}.xml"
    t0 = time.monotonic()
    res = subprocess.run([*RAPIDGEN, "conform", str(DESCRIPTORS[asset]), "--domain", str(domain),
                          "--json", str(report), "--junit", str(junit), *extra],
                         cwd=ROOT, env=env_for(pydir, SEEDS[asset]), capture_output=True, text=True, timeout=240)
    data = json.loads(report.read_text()) if report.exists() else None
    return {"code": res.returncode, "stdout": res.stdout, "stderr": res.stderr, "report": data, "junit": junit,
            "seconds": time.monotonic() - t0}


def broken_bridge(kind: str, asset: str, domain: int) -> BridgeProcess:
    """A BridgeProcess running tests/conformance/broken.py instead of the package's bridge."""
    pydir, package = python_dir(asset), SEEDS[asset]
    env = dict(env_for(pydir, package), BROKEN_SECONDS="180")
    return BridgeProcess.of_command([sys.executable, "-m", "tests.conformance.broken", kind, str(pydir), package,
                                     str(domain)], ROOT, env)


def outcomes(report: dict) -> dict[str, str]:
    return {c["id"]: c["outcome"] for c in report["checks"]}


__all__ = ["DOMAIN_BASE", "BridgeProcess", "broken_bridge", "conform", "outcomes", "os"]
