"""Run a Cyclone DDS reader of OLD against a writer of NEW, on loopback, for many pairs at once.

Each side's IDL is compiled with `rapidgen generate --lang python` into its own package;
each pair gets its own DDS domain id, so the pairs run in parallel without seeing each other.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

from rapidgen.cli import main as rapidgen_main

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LOOPBACK_XML = os.path.join(REPO, "tests", "interop", "cyclonedds-loopback.xml")


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["CYCLONEDDS_URI"] = "file://" + LOOPBACK_XML
    env["PYTHONPATH"] = REPO
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    return env


def build(tmp: str, name: str, idl_text: str) -> str:
    """Generate bindings for one side; returns the folder holding package `name`."""
    os.makedirs(tmp, exist_ok=True)
    src = os.path.join(tmp, f"{name}.idl")
    with open(src, "w", encoding="utf-8") as f:
        f.write(idl_text)
    out = os.path.join(tmp, f"out_{name}")
    assert rapidgen_main(["generate", src, "--lang", "python", "-o", out, "--package", name]) == 0
    return os.path.join(out, "python")


def exchange(tmp: str, pairs: list[tuple[str, str, str]], first_domain: int, timeout: float = 4.0) -> list[dict]:
    """For each (old IDL, new IDL, scoped type): {"matched": reader and writer matched,
    "received": the reader got a sample}. All pairs run at the same time."""
    procs = []
    for i, (old, new, type_) in enumerate(pairs):
        old_dir, new_dir = build(tmp, f"old{i}", old), build(tmp, f"new{i}", new)
        for role, d, pkg in (("reader", old_dir, f"old{i}"), ("writer", new_dir, f"new{i}")):
            cmd = [sys.executable, "-m", "tests.diff.live_peer", role, d, pkg, type_,
                   "--domain", str(first_domain + i), "--timeout", str(timeout)]
            procs.append(subprocess.Popen(cmd, cwd=REPO, env=_env(), stdout=subprocess.PIPE,
                                          stderr=subprocess.PIPE, text=True))
    outs = []
    try:
        for p in procs:
            out, err = p.communicate(timeout=timeout + 20)
            line = (out.strip().splitlines() or ["{}"])[-1]
            outs.append(json.loads(line) if line.startswith("{") else {"error": err[-2000:]})
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
                p.communicate(timeout=10)
    results = []
    for i in range(len(pairs)):
        r, w = outs[2 * i], outs[2 * i + 1]
        if "error" in r or "error" in w:
            raise AssertionError(f"pair {i}: {r.get('error') or w.get('error')}")
        results.append({"matched": bool(r["matched"] and w["matched"]), "received": r["received"] is not None})
    return results
